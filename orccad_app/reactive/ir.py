"""The reactive kernel: a small Esterel-like intermediate representation.

Every statement of the plan language lowers to these kernel statements (see
:mod:`orccad_app.reactive.derived` for the derived forms: ``await``, ``every``, ``abort``,
``repeat`` …). The kernel is the one of Esterel v5 with data:

===============  ==============================================================
``Nothing``      terminates at once
``Pause``        waits for the next instant
``Emit``         makes a signal present in this instant (optionally with a value)
``Present``      branches on a test: signal presence or a data condition
``Seq``          runs its items one after the other
``Loop``         restarts its body each time it terminates (never instantaneous)
``Par``          runs branches together; terminates when all have terminated
``Trap``/``Exit``  weak preemption by an exception; the trap catches its exits
``Suspend``      freezes its body in an instant (after the first) where a test holds
``Local``        declares local signals for its body
``Assign``       assigns a data variable
===============  ==============================================================

Tests (``Test``) are signal expressions over presence (:class:`SigRef`, :class:`SigNot`,
:class:`SigAnd`, :class:`SigOr`) or a data condition (:class:`DataTest`). Data expressions
(:class:`Expr`) are evaluated at run time only: counters and timers are data, not states.
Every node carries the :class:`~orccad_app.diagnostics.SourceLocation` of the source construct
it comes from, so compile errors point at the user's text.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Hashable, Union

from orccad_app.diagnostics import NOWHERE, SourceLocation

__all__ = [
    "SignalDecl", "VarDecl", "TrapDecl",
    "Const", "VarRef", "SigValue", "PreValue", "Fault", "Clock", "Unary", "Binary", "VectorExpr", "Expr",
    "SigRef", "PreRef", "SigNot", "SigAnd", "SigOr", "DataTest", "Test",
    "Nothing", "Pause", "Emit", "Present", "Seq", "Loop", "Par", "Trap", "Exit",
    "Suspend", "Local", "Assign", "Mark", "Stmt", "Program",
    "INPUT", "OUTPUT", "LOCAL", "Relation", "NO_VALUE",
]

INPUT, OUTPUT, LOCAL = "input", "output", "local"


class _NoValue:
    """The value of a signal that never had one (a fresh incarnation without initial value)."""

    def __repr__(self) -> str:
        return "no value"


#: Stored as the value of a fresh local signal without initial value: reading it is an error.
NO_VALUE = _NoValue()


# --------------------------------------------------------------------------- declarations

@dataclass(frozen=True, slots=True, eq=False)
class SignalDecl:
    """A signal: ``kind`` is ``input``, ``output`` or ``local``; ``type`` is ``None`` if pure.

    Declarations compare by identity: two local signals with the same name are different.
    """

    name: str
    kind: str
    type: str | None = None
    loc: SourceLocation = NOWHERE
    #: the initial value (a Python value) of ``?S`` before any emission; ``None``: none
    init: Any = None
    #: how the emissions of one instant combine (``+ * min max and or``); ``None``: a second
    #: emission in an instant is an error
    combine: str | None = None

    @property
    def valued(self) -> bool:
        return self.type is not None


@dataclass(frozen=True, slots=True, eq=False)
class VarDecl:
    """A data variable (user ``var`` or a hidden counter/deadline made by a derived form)."""

    name: str
    loc: SourceLocation = NOWHERE
    hidden: bool = False


@dataclass(frozen=True, slots=True, eq=False)
class TrapDecl:
    """A trap (exception) name; ``exit`` refers to the declaration, not the name."""

    name: str
    loc: SourceLocation = NOWHERE


# --------------------------------------------------------------------------- data expressions

@dataclass(frozen=True, slots=True, eq=False)
class Const:
    value: Any
    loc: SourceLocation = NOWHERE


@dataclass(frozen=True, slots=True, eq=False)
class VarRef:
    var: VarDecl
    loc: SourceLocation = NOWHERE


@dataclass(frozen=True, slots=True, eq=False)
class SigValue:
    """``?S``: the value of S emitted in this instant, else its last value."""

    signal: SignalDecl
    loc: SourceLocation = NOWHERE


@dataclass(frozen=True, slots=True, eq=False)
class PreValue:
    """``pre(?S)``: the value of S at the end of the previous instant (its initial value at
    the first instant)."""

    signal: SignalDecl
    loc: SourceLocation = NOWHERE


@dataclass(frozen=True, slots=True, eq=False)
class Fault:
    """A run-time error raised when evaluated (made by the compiler, e.g. for two emissions of
    a valued signal without ``combine`` in an instant the compiler could not rule out)."""

    message: str
    loc: SourceLocation = NOWHERE


@dataclass(frozen=True, slots=True, eq=False)
class Clock:
    """The executive clock of the current instant, in integer nanoseconds."""

    loc: SourceLocation = NOWHERE


@dataclass(frozen=True, slots=True, eq=False)
class Unary:
    op: str  # "-", "not"
    operand: "Expr"
    loc: SourceLocation = NOWHERE


@dataclass(frozen=True, slots=True, eq=False)
class Binary:
    op: str  # + - * / < <= > >= == != and or
    left: "Expr"
    right: "Expr"
    loc: SourceLocation = NOWHERE


@dataclass(frozen=True, slots=True, eq=False)
class VectorExpr:
    items: tuple["Expr", ...]
    loc: SourceLocation = NOWHERE


Expr = Union[Const, VarRef, SigValue, PreValue, Fault, Clock, Unary, Binary, VectorExpr]


# --------------------------------------------------------------------------- tests

@dataclass(frozen=True, slots=True, eq=False)
class SigRef:
    signal: SignalDecl
    loc: SourceLocation = NOWHERE


@dataclass(frozen=True, slots=True, eq=False)
class PreRef:
    """``pre(S)``: S was present in the previous instant (absent at the first instant of the
    program, or of the incarnation of a local signal)."""

    signal: SignalDecl
    loc: SourceLocation = NOWHERE


@dataclass(frozen=True, slots=True, eq=False)
class SigNot:
    operand: "Test"
    loc: SourceLocation = NOWHERE


@dataclass(frozen=True, slots=True, eq=False)
class SigAnd:
    left: "Test"
    right: "Test"
    loc: SourceLocation = NOWHERE


@dataclass(frozen=True, slots=True, eq=False)
class SigOr:
    left: "Test"
    right: "Test"
    loc: SourceLocation = NOWHERE


@dataclass(frozen=True, slots=True, eq=False)
class DataTest:
    """A condition on data (variables, ``?S``, the clock), decided at run time."""

    expr: Expr
    loc: SourceLocation = NOWHERE


Test = Union[SigRef, PreRef, SigNot, SigAnd, SigOr, DataTest]


# --------------------------------------------------------------------------- statements

@dataclass(frozen=True, slots=True, eq=False)
class Nothing:
    loc: SourceLocation = NOWHERE


@dataclass(frozen=True, slots=True, eq=False)
class Pause:
    loc: SourceLocation = NOWHERE


@dataclass(frozen=True, slots=True, eq=False)
class Emit:
    signal: SignalDecl
    value: Expr | None = None
    loc: SourceLocation = NOWHERE


@dataclass(frozen=True, slots=True, eq=False)
class Present:
    test: Test
    then: "Stmt"
    orelse: "Stmt" = field(default_factory=Nothing)
    loc: SourceLocation = NOWHERE


@dataclass(frozen=True, slots=True, eq=False)
class Seq:
    items: tuple["Stmt", ...]
    loc: SourceLocation = NOWHERE


@dataclass(frozen=True, slots=True, eq=False)
class Loop:
    """``what`` names the source construct in the instantaneous-loop diagnostic."""

    body: "Stmt"
    loc: SourceLocation = NOWHERE
    what: str = "loop"


@dataclass(frozen=True, slots=True, eq=False)
class Par:
    branches: tuple["Stmt", ...]
    loc: SourceLocation = NOWHERE


@dataclass(frozen=True, slots=True, eq=False)
class Trap:
    trap: TrapDecl
    body: "Stmt"
    loc: SourceLocation = NOWHERE


@dataclass(frozen=True, slots=True, eq=False)
class Exit:
    trap: TrapDecl
    loc: SourceLocation = NOWHERE


@dataclass(frozen=True, slots=True, eq=False)
class Suspend:
    """Non-immediate suspension (the immediate form is derived)."""

    test: Test
    body: "Stmt"
    loc: SourceLocation = NOWHERE


@dataclass(frozen=True, slots=True, eq=False)
class Local:
    signals: tuple[SignalDecl, ...]
    body: "Stmt"
    loc: SourceLocation = NOWHERE


@dataclass(frozen=True, slots=True, eq=False)
class Assign:
    var: VarDecl
    expr: Expr
    loc: SourceLocation = NOWHERE


@dataclass(frozen=True, slots=True, eq=False)
class Mark:
    """A transparent region with a label: no behaviour of its own.

    A control state is *in* the region when one of its active pauses is inside ``body``; the
    compiled automaton lists, for each state, the labels of the regions it is in (e.g. which
    Robot-Task instance is active, and in which phase).
    """

    label: Hashable
    body: "Stmt"
    loc: SourceLocation = NOWHERE


Stmt = Union[Nothing, Pause, Emit, Present, Seq, Loop, Par, Trap, Exit, Suspend, Local, Assign,
             Mark]


@dataclass(frozen=True, slots=True, eq=False)
class Relation:
    """An assumption on the inputs of every instant: ``A # B # C`` (``kind`` ``"#"``: at most
    one present) or ``A => B`` (``kind`` ``"=>"``: A present implies B present)."""

    kind: str
    signals: tuple[SignalDecl, ...]
    loc: SourceLocation = NOWHERE

    @property
    def text(self) -> str:
        return f" {self.kind} ".join(s.name for s in self.signals)

    def holds(self, present) -> bool:
        """Whether a set of present input *names* satisfies the relation."""
        names = [s.name in present for s in self.signals]
        if self.kind == "#":
            return sum(names) <= 1
        return not names[0] or names[1]


@dataclass(frozen=True, slots=True, eq=False)
class Program:
    """A compilable reactive program: its interface signals, in declaration order, and body.

    ``failed`` and ``aborted`` are hidden valued outputs (the exception's name): emitting one
    gives the instant the status ``failed`` or ``aborted`` (see the application level).
    """

    name: str
    inputs: tuple[SignalDecl, ...]
    outputs: tuple[SignalDecl, ...]
    body: Stmt
    loc: SourceLocation = NOWHERE
    failed: SignalDecl | None = None
    aborted: SignalDecl | None = None
    relations: tuple[Relation, ...] = ()
