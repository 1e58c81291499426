"""Robot-Task nodes of the plan language AST (re-exported by :mod:`orccad_app.lang.ast`)."""

from __future__ import annotations

import enum

from orccad_app.diagnostics import NOWHERE, SourceLocation
from orccad_app.lang.ast_expr import Arg, Call, Expr, node

__all__ = ["PROTOCOLS", "DEFAULT_PROTOCOL", "Param", "PortRef", "Module", "Connect",
           "SignalPrecondition", "MeasurePrecondition", "ExceptionType", "Adjust",
           "ExceptionDecl", "MeasurePostcondition", "SignalPostcondition", "AutomatonPlacement",
           "RobotTask"]

#: Port-to-port communication protocols (docs/design.md).
PROTOCOLS: tuple[str, ...] = (
    "asyn/asyn", "syn/syn", "asyn/syn", "syn/asyn",
    "asyn/synF", "synF/asyn", "asyn/synD", "asyn/synDF",
)
DEFAULT_PROTOCOL = "asyn/asyn"


@node
class Param:
    """A Robot-Task parameter ``name: type = default`` (type and default optional)."""

    name: str
    type: str | None = None
    default: Expr | None = None
    loc: SourceLocation = NOWHERE


# --------------------------------------------------------------------------- Robot-Tasks

@node
class PortRef:
    """``component.port`` (a module or the robot, and one of its ports or parameters)."""

    component: str
    port: str
    loc: SourceLocation = NOWHERE


@node
class Module:
    """``module NAME : KIND(args) period .. wcet .. [bcet ..] on CPU priority N;``.

    Omitted timing parts are ``None`` (the law's defaults apply). ``sporadic min_interarrival
    D`` instead of ``period`` makes it sporadic (``min_interarrival_ns``: released by
    interrupts, at least that far apart).
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
    min_interarrival_ns: int | None = None


@node
class Connect:
    """``connect a.b -> c.d [: protocol];`` (protocol one of :data:`PROTOCOLS`)."""

    source: PortRef
    target: PortRef
    protocol: str = DEFAULT_PROTOCOL
    loc: SourceLocation = NOWHERE


@node
class SignalPrecondition:
    """``precondition S;`` - synchronization pre-condition: wait for signal ``S``."""

    signal: str
    loc: SourceLocation = NOWHERE


@node
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


@node
class Adjust:
    """``adjust module.param = value`` of a type-1 exception."""

    target: PortRef
    value: Expr
    loc: SourceLocation = NOWHERE


@node
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


@node
class MeasurePostcondition:
    """``postcondition measure obs(args);``."""

    observer: Call
    loc: SourceLocation = NOWHERE


@node
class SignalPostcondition:
    """``postcondition emit S;`` - emitted at the good end."""

    signal: str
    loc: SourceLocation = NOWHERE


@node
class AutomatonPlacement:
    """``automaton on CPU [reaction D];``: the processor the Robot-Task's behaviour automaton
    reacts on, and the execution time of a reaction there (``reaction_ns``, 0 when omitted).
    An observer on another processor sends its signals over the bus."""

    processor: str
    reaction_ns: int = 0
    loc: SourceLocation = NOWHERE


@node
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
    automaton: AutomatonPlacement | None = None

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
