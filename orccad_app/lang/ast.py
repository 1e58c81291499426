"""The plan language's abstract syntax tree: frozen dataclasses with source positions.

Every node is a ``frozen``, ``slots``, ``kw_only`` dataclass whose last field is
``loc: SourceLocation`` (default :data:`~orccad_app.diagnostics.NOWHERE`, so tests may build
nodes by hand: ``Emit(signal="O")``). Sequences are tuples, so nodes are hashable and compare
by value (the location included). Durations are integer nanoseconds (``*_ns`` fields).
This module depends on nothing but the standard library and :mod:`orccad_app.diagnostics`.

Layout
------
:class:`Program` (alias :data:`SourceFile`) is the root. ``items`` keeps every top-level
declaration in source order; ``robots``, ``signals``, ``robottasks``, ``missions``,
``properties`` and ``assumptions`` are filtered views of it.

Conditions: signal presence or data
-----------------------------------
``if``, ``await``, ``every``, ``abort``/``suspend ... when`` and ``loop ... each`` take one
:data:`Expr`. The parser cannot tell ``S`` (a signal: presence test) from ``x`` (a variable:
a value), so both are :class:`Name`. The checker (:func:`orccad_app.lang.names.check`) resolves
them: ``CheckResult.kind_of(name_node)`` gives a :class:`~orccad_app.lang.names.NameKind` for
every identifier of a mission, and ``CheckResult.condition_kind(expr)`` says whether a
condition is a presence test (only signal names under ``not``/``and``/``or``) or a data
expression. :func:`orccad_app.lang.names.classify_condition` does the same from a plain
``{name: NameKind}`` scope. ``?S`` (:class:`LastValue`) is always data.

Triggers
--------
``await``, ``every``, ``abort``, ``suspend`` and ``loop ... each`` share a :class:`Trigger`:
``await immediate S`` → ``Trigger(condition=Name("S"), immediate=True)``, ``await 3 S`` →
``count=Number(3)``, ``await 2.5 s`` → ``duration_ns=2_500_000_000`` (``condition`` is
``None``). :class:`Await` also exposes the trigger's fields directly.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass
from typing import Union

from orccad_app.diagnostics import NOWHERE, SourceLocation

__all__ = [
    # expressions
    "Name", "Number", "String", "Bool", "Vector", "DurationLit", "LastValue", "Unary",
    "Binary", "Call", "Arg", "Expr",
    # declarations
    "SignalDecl", "Direction", "Robot", "Param",
    # Robot-Tasks
    "PortRef", "Module", "Connect", "SignalPrecondition", "MeasurePrecondition",
    "ExceptionType", "Adjust", "ExceptionDecl", "MeasurePostcondition",
    "SignalPostcondition", "RobotTask", "PROTOCOLS", "DEFAULT_PROTOCOL",
    # statements
    "Trigger", "Block", "Nothing", "Pause", "Halt", "Emit", "Sustain", "Await", "Run", "If",
    "Loop", "Repeat", "Every", "Abort", "Suspend", "Trap", "Exit", "Catch", "Try", "Par",
    "Race", "LocalSignals", "VarDecl", "Assign", "Stmt",
    # missions, properties, root
    "Mission", "FSignal", "FPredicate", "FStatus", "FBool", "FUnary", "FBinary", "Formula",
    "Property", "Assumption", "Program", "SourceFile", "TopItem", "VALUE_TYPES",
]

_node = dataclass(frozen=True, slots=True, kw_only=True)

#: Value types of signals, variables and parameters.
VALUE_TYPES: frozenset[str] = frozenset({"int", "float", "bool", "string", "vector", "duration"})

#: Port-to-port communication protocols (DESIGN.md §5).
PROTOCOLS: tuple[str, ...] = (
    "asyn/asyn", "syn/syn", "asyn/syn", "syn/asyn",
    "asyn/synF", "synF/asyn", "asyn/synD", "asyn/synDF",
)
DEFAULT_PROTOCOL = "asyn/asyn"


# --------------------------------------------------------------------------- expressions

@_node
class Name:
    """An identifier in an expression: a signal (presence), a variable or a parameter."""

    name: str
    loc: SourceLocation = NOWHERE


@_node
class Number:
    """A numeric literal; ``value`` is ``int`` when written without ``.``/exponent.

    A leading minus is folded in (``-0.5`` is ``Number(value=-0.5, text="-0.5")``); the
    constant ``pi`` is ``Number(value=math.pi, text="pi")``.
    """

    value: int | float
    text: str = ""
    loc: SourceLocation = NOWHERE


@_node
class String:
    """A string literal, escapes resolved."""

    value: str
    loc: SourceLocation = NOWHERE


@_node
class Bool:
    """``true`` or ``false``."""

    value: bool
    loc: SourceLocation = NOWHERE


@_node
class Vector:
    """``[e1, e2, ...]``."""

    items: tuple[Expr, ...]
    loc: SourceLocation = NOWHERE


@_node
class DurationLit:
    """A duration literal such as ``2.5 s``, in integer nanoseconds."""

    duration_ns: int
    text: str = ""
    loc: SourceLocation = NOWHERE


@_node
class LastValue:
    """``?S``: the last value of the valued signal ``S``."""

    signal: str
    loc: SourceLocation = NOWHERE


@_node
class Unary:
    """``op operand`` with ``op`` in ``"-"``, ``"not"``."""

    op: str
    operand: Expr
    loc: SourceLocation = NOWHERE


@_node
class Binary:
    """``left op right``; ``op`` is one of ``+ - * / < <= > >= == != and or``."""

    op: str
    left: Expr
    right: Expr
    loc: SourceLocation = NOWHERE


@_node
class Arg:
    """One argument of a call: ``name = value`` or positional (``name`` is ``None``)."""

    name: str | None
    value: Expr
    loc: SourceLocation = NOWHERE


@_node
class Call:
    """``func(args)``: a parameterized kind (law, observer, trajectory...) or function."""

    func: str
    args: tuple[Arg, ...] = ()
    loc: SourceLocation = NOWHERE

    def arg(self, name: str) -> Arg | None:
        """The named argument ``name``, or ``None``."""
        return next((a for a in self.args if a.name == name), None)


Expr = Union[Name, Number, String, Bool, Vector, DurationLit, LastValue, Unary, Binary, Call]


# --------------------------------------------------------------------------- declarations

class Direction(str, enum.Enum):
    """Where a signal comes from."""

    INPUT = "input"    #: from the environment or the operator; never emitted by the plan
    OUTPUT = "output"  #: emitted by the plan
    LOCAL = "local"    #: declared by a ``signal S { ... }`` statement


@_node
class SignalDecl:
    """One signal: ``input A``, ``output Done : string``, or a local ``signal S``.

    ``type`` is ``None`` for a pure signal, else a value type name (``"float"``...).
    """

    name: str
    direction: Direction
    type: str | None = None
    loc: SourceLocation = NOWHERE

    @property
    def valued(self) -> bool:
        """Whether the signal carries a value."""
        return self.type is not None


@_node
class Robot:
    """``robot NAME : TYPE(params);`` - a physical resource of a plugin-provided type."""

    name: str
    type: str
    args: tuple[Arg, ...] = ()
    loc: SourceLocation = NOWHERE


@_node
class Param:
    """A Robot-Task parameter ``name: type = default`` (type and default optional)."""

    name: str
    type: str | None = None
    default: Expr | None = None
    loc: SourceLocation = NOWHERE


# --------------------------------------------------------------------------- Robot-Tasks

@_node
class PortRef:
    """``component.port`` (a module or the robot, and one of its ports or parameters)."""

    component: str
    port: str
    loc: SourceLocation = NOWHERE


@_node
class Module:
    """``module NAME : KIND(args) period .. wcet .. [bcet ..] on CPU priority N;``.

    Omitted timing parts are ``None`` (the law's defaults apply).
    """

    name: str
    kind: str
    args: tuple[Arg, ...] = ()
    period_ns: int | None = None
    wcet_ns: int | None = None
    bcet_ns: int | None = None
    processor: str | None = None
    priority: int | None = None
    loc: SourceLocation = NOWHERE


@_node
class Connect:
    """``connect a.b -> c.d [: protocol];`` (protocol one of :data:`PROTOCOLS`)."""

    source: PortRef
    target: PortRef
    protocol: str = DEFAULT_PROTOCOL
    loc: SourceLocation = NOWHERE


@_node
class SignalPrecondition:
    """``precondition S;`` - synchronization pre-condition: wait for signal ``S``."""

    signal: str
    loc: SourceLocation = NOWHERE


@_node
class MeasurePrecondition:
    """``precondition measure obs(args) [within DUR];`` - measurement pre-condition."""

    observer: Call
    within_ns: int | None = None
    loc: SourceLocation = NOWHERE


class ExceptionType(str, enum.Enum):
    """Exception handling types of RR-1801 §3.4.2; ``number`` is the paper's type."""

    ADJUST = "adjust"  #: type 1: change a module parameter, the task goes on
    ABORT = "abort"    #: type 2: kill the RT, signal the application
    FATAL = "fatal"    #: type 3: kill the RT and the whole application

    @property
    def number(self) -> int:
        """1, 2 or 3."""
        return {"adjust": 1, "abort": 2, "fatal": 3}[self.value]


@_node
class Adjust:
    """``adjust module.param = value`` of a type-1 exception."""

    target: PortRef
    value: Expr
    loc: SourceLocation = NOWHERE


@_node
class ExceptionDecl:
    """``exception NAME from SOURCE : fatal|abort|adjust m.p = e;``.

    ``source`` names a declared module of the task or an observer kind; ``source.args`` is
    empty when written without parentheses (``from jl``).
    """

    name: str
    source: Call
    type: ExceptionType
    adjust: Adjust | None = None
    loc: SourceLocation = NOWHERE


@_node
class MeasurePostcondition:
    """``postcondition measure obs(args);``."""

    observer: Call
    loc: SourceLocation = NOWHERE


@_node
class SignalPostcondition:
    """``postcondition emit S;`` - emitted at the good end."""

    signal: str
    loc: SourceLocation = NOWHERE


@_node
class RobotTask:
    """``robottask NAME(params) on ROBOT { ... }``, its items grouped by kind."""

    name: str
    params: tuple[Param, ...]
    robot: str
    duration_ns: int | None = None
    task_function: Call | None = None
    law: Call | None = None
    modules: tuple[Module, ...] = ()
    connections: tuple[Connect, ...] = ()
    preconditions: tuple[SignalPrecondition | MeasurePrecondition, ...] = ()
    exceptions: tuple[ExceptionDecl, ...] = ()
    postconditions: tuple[MeasurePostcondition | SignalPostcondition, ...] = ()
    loc: SourceLocation = NOWHERE

    def module(self, name: str) -> Module | None:
        """The module called ``name``, or ``None``."""
        return next((m for m in self.modules if m.name == name), None)

    def param(self, name: str) -> Param | None:
        """The parameter called ``name``, or ``None``."""
        return next((p for p in self.params if p.name == name), None)

    def raisable(self) -> tuple[str, ...]:
        """Names a ``run`` of this task can raise in the application (type 2).

        The ``abort`` exceptions, then ``OBSERVER_timeout`` for each measurement
        pre-condition with a watchdog. (``Timeout`` comes from ``run ... within``.)
        """
        names = [e.name for e in self.exceptions if e.type is ExceptionType.ABORT]
        names += [f"{p.observer.func}_timeout" for p in self.preconditions
                  if isinstance(p, MeasurePrecondition) and p.within_ns is not None]
        return tuple(names)


# --------------------------------------------------------------------------- statements

@_node
class Trigger:
    """What ``await``/``every``/``when``/``each`` wait for.

    Exactly one of ``condition`` (a signal or data :data:`Expr`) and ``duration_ns`` is set.
    ``count`` (``await 3 S``) is only set with a condition; ``immediate`` also looks at the
    current instant.
    """

    condition: Expr | None = None
    immediate: bool = False
    count: Expr | None = None
    duration_ns: int | None = None
    loc: SourceLocation = NOWHERE


@_node
class Block:
    """``{ s1 s2 ... }``: a sequence."""

    statements: tuple[Stmt, ...] = ()
    loc: SourceLocation = NOWHERE


@_node
class Nothing:
    """``nothing;`` - terminates at once."""

    loc: SourceLocation = NOWHERE


@_node
class Pause:
    """``pause;`` - waits one instant."""

    loc: SourceLocation = NOWHERE


@_node
class Halt:
    """``halt;`` - never terminates."""

    loc: SourceLocation = NOWHERE


@_node
class Emit:
    """``emit S;`` or ``emit S(value);``; ``signal_loc`` points at ``S``."""

    signal: str
    value: Expr | None = None
    signal_loc: SourceLocation = NOWHERE
    loc: SourceLocation = NOWHERE


@_node
class Sustain:
    """``sustain S;`` or ``sustain S(value);`` - emits S in every instant, forever."""

    signal: str
    value: Expr | None = None
    signal_loc: SourceLocation = NOWHERE
    loc: SourceLocation = NOWHERE


@_node
class Await:
    """``await [immediate] [N] S;``, ``await (S and not T);``, ``await 2.5 s;``."""

    trigger: Trigger
    loc: SourceLocation = NOWHERE

    @property
    def condition(self) -> Expr | None:
        return self.trigger.condition

    @property
    def immediate(self) -> bool:
        return self.trigger.immediate

    @property
    def count(self) -> Expr | None:
        return self.trigger.count

    @property
    def duration_ns(self) -> int | None:
        return self.trigger.duration_ns


@_node
class Run:
    """``run RT(args) [within DUR];``; ``task_loc`` points at the task's name."""

    task: str
    args: tuple[Arg, ...] = ()
    within_ns: int | None = None
    task_loc: SourceLocation = NOWHERE
    loc: SourceLocation = NOWHERE


@_node
class If:
    """``if COND { ... } [else { ... }]``; ``else if`` is an ``orelse`` block holding an If."""

    condition: Expr
    then: Block
    orelse: Block | None = None
    loc: SourceLocation = NOWHERE


@_node
class Loop:
    """``loop { ... }`` or ``loop { ... } each TRIGGER;``."""

    body: Block
    each: Trigger | None = None
    loc: SourceLocation = NOWHERE


@_node
class Repeat:
    """``repeat N { ... }``."""

    count: Expr
    body: Block
    loc: SourceLocation = NOWHERE


@_node
class Every:
    """``every TRIGGER { ... }`` - restart the body at each occurrence."""

    trigger: Trigger
    body: Block
    loc: SourceLocation = NOWHERE


@_node
class Abort:
    """``[weak] abort { ... } when TRIGGER [do { ... }];``."""

    body: Block
    trigger: Trigger
    weak: bool = False
    handler: Block | None = None
    loc: SourceLocation = NOWHERE


@_node
class Suspend:
    """``suspend { ... } when TRIGGER;``."""

    body: Block
    trigger: Trigger
    loc: SourceLocation = NOWHERE


@_node
class Trap:
    """``trap T { ... } [handle { ... }]``."""

    name: str
    body: Block
    handler: Block | None = None
    loc: SourceLocation = NOWHERE


@_node
class Exit:
    """``exit T;``."""

    name: str
    loc: SourceLocation = NOWHERE


@_node
class Catch:
    """``catch E1, E2 { ... }`` of a :class:`Try`."""

    exceptions: tuple[str, ...]
    body: Block
    loc: SourceLocation = NOWHERE


@_node
class Try:
    """``try { ... } catch ... { ... } ...``."""

    body: Block
    catches: tuple[Catch, ...]
    loc: SourceLocation = NOWHERE


@_node
class Par:
    """``par { ... } || { ... }`` - terminates when all branches have."""

    branches: tuple[Block, ...]
    loc: SourceLocation = NOWHERE


@_node
class Race:
    """``race { ... } || { ... }`` - the first branch to terminate kills the others."""

    branches: tuple[Block, ...]
    loc: SourceLocation = NOWHERE


@_node
class LocalSignals:
    """``signal S, T [: type] { ... }`` - local signals (``direction`` is LOCAL)."""

    signals: tuple[SignalDecl, ...]
    body: Block
    loc: SourceLocation = NOWHERE


@_node
class VarDecl:
    """``var x [: type] := value;`` - visible to the end of the enclosing block."""

    name: str
    value: Expr
    type: str | None = None
    loc: SourceLocation = NOWHERE


@_node
class Assign:
    """``x := value;``."""

    name: str
    value: Expr
    loc: SourceLocation = NOWHERE


Stmt = Union[Block, Nothing, Pause, Halt, Emit, Sustain, Await, Run, If, Loop, Repeat, Every,
             Abort, Suspend, Trap, Exit, Try, Par, Race, LocalSignals, VarDecl, Assign]


# --------------------------------------------------------------------------- missions

@_node
class Mission:
    """``mission NAME { declarations and statements [on fatal { ... }] }``.

    ``signals`` are the mission-level ``input``/``output`` declarations in source order;
    ``body`` holds the statements.
    """

    name: str
    signals: tuple[SignalDecl, ...]
    body: Block
    on_fatal: Block | None = None
    loc: SourceLocation = NOWHERE


# --------------------------------------------------------------------------- temporal logic

@_node
class FSignal:
    """A signal name in a formula: present in the instant."""

    name: str
    loc: SourceLocation = NOWHERE


@_node
class FPredicate:
    """``active(RT)``, ``started(RT)``, ``ended(RT)`` or ``raised(E)``."""

    predicate: str
    argument: str
    loc: SourceLocation = NOWHERE


@_node
class FStatus:
    """``done``, ``failed`` or ``aborted``: the mission's status."""

    status: str
    loc: SourceLocation = NOWHERE


@_node
class FBool:
    """``true`` or ``false``."""

    value: bool
    loc: SourceLocation = NOWHERE


@_node
class FUnary:
    """``op f``; op in not, next, always, eventually, never, previously, once, historically."""

    op: str
    operand: Formula
    loc: SourceLocation = NOWHERE


@_node
class FBinary:
    """``f op g``; op in ``and``, ``or``, ``->``, ``<->``, ``until``, ``since``."""

    op: str
    left: Formula
    right: Formula
    loc: SourceLocation = NOWHERE


Formula = Union[FSignal, FPredicate, FStatus, FBool, FUnary, FBinary]


@_node
class Property:
    """``property MISSION.NAME: formula;`` (``mission`` is ``None`` when written
    ``property NAME: ...``: it then applies to every mission of the file)."""

    mission: str | None
    name: str
    formula: Formula
    loc: SourceLocation = NOWHERE


@_node
class Assumption:
    """``assume MISSION.NAME: formula;`` - an environment assumption, same syntax."""

    mission: str | None
    name: str
    formula: Formula
    loc: SourceLocation = NOWHERE


# --------------------------------------------------------------------------- root

TopItem = Union[Robot, SignalDecl, RobotTask, Mission, Property, Assumption]


@_node
class Program:
    """One ``.orc`` file: every top-level item in source order, and views by kind."""

    filename: str
    items: tuple[TopItem, ...] = ()
    loc: SourceLocation = NOWHERE

    def _of(self, kind: type) -> tuple:
        return tuple(item for item in self.items if isinstance(item, kind))

    @property
    def robots(self) -> tuple[Robot, ...]:
        return self._of(Robot)

    @property
    def signals(self) -> tuple[SignalDecl, ...]:
        """File-level ``input``/``output`` declarations (visible in every mission)."""
        return self._of(SignalDecl)

    @property
    def robottasks(self) -> tuple[RobotTask, ...]:
        return self._of(RobotTask)

    @property
    def missions(self) -> tuple[Mission, ...]:
        return self._of(Mission)

    @property
    def properties(self) -> tuple[Property, ...]:
        return self._of(Property)

    @property
    def assumptions(self) -> tuple[Assumption, ...]:
        return self._of(Assumption)

    def mission(self, name: str) -> Mission | None:
        """The mission called ``name``, or ``None``."""
        return next((m for m in self.missions if m.name == name), None)

    def robottask(self, name: str) -> RobotTask | None:
        """The Robot-Task called ``name``, or ``None``."""
        return next((t for t in self.robottasks if t.name == name), None)


SourceFile = Program
