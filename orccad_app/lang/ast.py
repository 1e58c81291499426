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

The nodes live in four modules (expressions in ``ast_expr``, Robot-Tasks in
``ast_robottask``, temporal logic in ``ast_formula``, the rest here); import them all from
here.
"""

from __future__ import annotations

import enum
from typing import Union

from orccad_app.diagnostics import NOWHERE, SourceLocation
from orccad_app.lang.ast_expr import (VALUE_TYPES, Arg, Binary, Bool, Call, DurationLit, Expr,
                                      LastValue, Name, Number, ParamRef, PreSignal, PreValue,
                                      String, Unary, Vector, node)
from orccad_app.lang.ast_formula import (Assumption, FBinary, FBool, FCompare, Formula,
                                         FPredicate, FSignal, FStatus, FUnary, Interval,
                                         Property, SArith, SCall, SignalExpr, SNeg, SNumber,
                                         SPort, SIGNAL_FUNCTIONS, formula_nodes,
                                         is_signal_formula)
from orccad_app.lang.ast_robottask import (DEFAULT_PROTOCOL, PROTOCOLS, Adjust,
                                           AutomatonPlacement, Connect,
                                           ExceptionDecl, ExceptionType, MeasurePostcondition,
                                           MeasurePrecondition, Module, Param, PortRef,
                                           RobotTask, SignalPostcondition,
                                           SignalPrecondition)

__all__ = [
    # expressions
    "Name", "Number", "String", "Bool", "Vector", "DurationLit", "LastValue", "PreSignal",
    "PreValue", "Unary",
    "Binary", "Call", "Arg", "ParamRef", "Expr",
    # declarations
    "SignalDecl", "Direction", "Robot", "Param", "Relation", "Import", "ImportedName",
    # Robot-Tasks
    "PortRef", "Module", "Connect", "SignalPrecondition", "MeasurePrecondition",
    "ExceptionType", "Adjust", "AutomatonPlacement", "ExceptionDecl", "MeasurePostcondition",
    "SignalPostcondition", "RobotTask", "PROTOCOLS", "DEFAULT_PROTOCOL",
    # statements
    "Trigger", "Block", "Nothing", "Pause", "Halt", "Emit", "Sustain", "Await", "Run", "If",
    "Loop", "Repeat", "Every", "Abort", "Suspend", "Trap", "Exit", "Catch", "Try", "Par",
    "Race", "LocalSignals", "VarDecl", "Assign", "RunMission", "Rename", "Fail", "Stmt",
    # missions, properties, root
    "Mission", "FSignal", "FPredicate", "FStatus", "FBool", "FUnary", "FBinary", "Formula",
    "FCompare", "Interval", "SPort", "SNumber", "SCall", "SNeg", "SArith", "SignalExpr",
    "is_signal_formula", "SIGNAL_FUNCTIONS", "formula_nodes",
    "Property", "Assumption", "Program", "SourceFile", "TopItem", "VALUE_TYPES",
]

_node = node


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
    ``init`` is the declared initial value (``output O : int := 0;``), ``combine`` how the
    emissions of one instant combine (``+ * min max and or``).
    """

    name: str
    direction: Direction
    type: str | None = None
    init: Expr | None = None
    combine: str | None = None
    loc: SourceLocation = NOWHERE

    @property
    def valued(self) -> bool:
        """Whether the signal carries a value."""
        return self.type is not None


@_node
class Relation:
    """``relation A # B # C;`` (``kind`` ``"#"``: never two together) or ``relation A => B;``
    (``kind`` ``"=>"``: A present implies B present), between input signals."""

    kind: str
    signals: tuple[str, ...]
    loc: SourceLocation = NOWHERE


@_node
class Robot:
    """``robot NAME : TYPE(params);`` - a physical resource of a plugin-provided type."""

    name: str
    type: str
    args: tuple[Arg, ...] = ()
    loc: SourceLocation = NOWHERE


@_node
class ImportedName:
    """One name of an ``import`` list."""

    name: str
    loc: SourceLocation = NOWHERE


@_node
class Import:
    """``from "PATH" import M1, M2;`` - missions of another file (``PATH`` relative to this
    one), resolved by :mod:`orccad_app.lang.imports`."""

    path: str
    names: tuple[ImportedName, ...]
    path_loc: SourceLocation = NOWHERE
    loc: SourceLocation = NOWHERE


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


@_node
class Rename:
    """``formal / actual`` in ``run mission M [...]``."""

    formal: str
    actual: str
    loc: SourceLocation = NOWHERE


@_node
class RunMission:
    """``run mission M [formal / actual, ...];`` - runs the sub-mission M, inlined, with its
    signals bound to the caller's (renamed ones, others by name)."""

    mission: str
    renames: tuple[Rename, ...] = ()
    mission_loc: SourceLocation = NOWHERE
    loc: SourceLocation = NOWHERE


@_node
class Fail:
    """``fail E;`` - raises exception E: caught by an enclosing ``try … catch E``, else the
    mission ends ``failed(E)``."""

    exception: str
    loc: SourceLocation = NOWHERE


Stmt = Union[Block, Nothing, Pause, Halt, Emit, Sustain, Await, Run, If, Loop, Repeat, Every,
             Abort, Suspend, Trap, Exit, Try, Par, Race, LocalSignals, VarDecl, Assign,
             RunMission, Fail]

# --------------------------------------------------------------------------- missions

@_node
class Mission:
    """``mission NAME { declarations and statements [on fatal { ... }] }``.

    ``signals`` are the mission-level ``input``/``output`` declarations in source order (the
    ``[signature]`` of a reusable sub-mission first); ``body`` holds the statements;
    ``relations`` the mission's own relations between inputs.
    """

    name: str
    signals: tuple[SignalDecl, ...]
    body: Block
    on_fatal: Block | None = None
    signature: tuple[SignalDecl, ...] = ()
    relations: tuple[Relation, ...] = ()
    loc: SourceLocation = NOWHERE

# --------------------------------------------------------------------------- root

TopItem = Union[Import, Robot, SignalDecl, Relation, RobotTask, Mission, Property,
                Assumption]


@_node
class Program:
    """One ``.orc`` file: every top-level item in source order, and views by kind.

    ``library`` holds what the file's ``import`` declarations bring (the imported missions,
    the missions and Robot-Tasks they run, the robots those run on: see
    :mod:`orccad_app.lang.imports`); ``missions`` are the file's own, ``robottasks`` and
    ``robots`` include the imported ones, :meth:`mission` finds both.
    """

    filename: str
    items: tuple[TopItem, ...] = ()
    library: tuple[TopItem, ...] = ()
    loc: SourceLocation = NOWHERE

    def _of(self, kind: type) -> tuple:
        return tuple(item for item in self.items if isinstance(item, kind))

    def _imported(self, kind: type) -> tuple:
        return tuple(item for item in self.library if isinstance(item, kind))

    @property
    def imports(self) -> tuple[Import, ...]:
        return self._of(Import)

    @property
    def robots(self) -> tuple[Robot, ...]:
        own = self._of(Robot)
        names = {robot.name for robot in own}
        return own + tuple(r for r in self._imported(Robot) if r.name not in names)

    @property
    def signals(self) -> tuple[SignalDecl, ...]:
        """File-level ``input``/``output`` declarations (visible in every mission)."""
        return self._of(SignalDecl)

    @property
    def relations(self) -> tuple[Relation, ...]:
        """File-level relations (assumed by every mission)."""
        return self._of(Relation)

    @property
    def robottasks(self) -> tuple[RobotTask, ...]:
        return self._of(RobotTask) + self._imported(RobotTask)

    @property
    def missions(self) -> tuple[Mission, ...]:
        """The file's own missions (those a command can select)."""
        return self._of(Mission)

    @property
    def imported_missions(self) -> tuple[Mission, ...]:
        """The missions ``import`` brought (runnable only as sub-missions)."""
        return self._imported(Mission)

    @property
    def properties(self) -> tuple[Property, ...]:
        return self._of(Property)

    @property
    def assumptions(self) -> tuple[Assumption, ...]:
        return self._of(Assumption)

    def mission(self, name: str) -> Mission | None:
        """The mission called ``name`` (the file's own or an imported one), or ``None``."""
        return next((m for m in self.missions + self.imported_missions if m.name == name),
                    None)

    def robottask(self, name: str) -> RobotTask | None:
        """The Robot-Task called ``name``, or ``None``."""
        return next((t for t in self.robottasks if t.name == name), None)


SourceFile = Program
