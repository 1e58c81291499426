"""The application level (RR-1801 §4): missions over Robot-Tasks, lowered to one automaton.

``run``, ``try … catch`` and ``on fatal`` are added to the reactive lowering, in one of two
*views* of the same mission:

``composed`` (the default: ``compile``, ``check``, ``run``)
    each ``run X(args)`` is replaced by an instance of X's generated RTA (:mod:`.rta`): the
    application automaton and the RTAs are flattened into one synchronous product. Its inputs
    are the observers' events (``X.TrackingLost``, ``X.at_goal``…) and the mission's inputs.

``abstract`` (``orccad react``: the mission's logic without the plant)
    each ``run X(args)`` emits ``X.start``, waits for its synchronization pre-conditions, then
    for the task's *outcome* as inputs: ``X.good_end`` (emitting its ``postcondition emit S``
    signals in that instant), its type-2 exceptions ``X.E`` (and ``X.<obs>_timeout``), its
    type-3 exceptions ``X.F``. Every mission-level output agrees with the composed view's
    (``tests/robottask/test_views_agree.py``).

In both views the output ``E.raised`` is present in the instant exception ``E`` is raised,
``X.start`` when task X starts (and, composed, ``X.good_end`` at its good end); each instance
of a task is a region labelled :class:`~orccad_app.robottask.labels.RtLabel` (composed: with
:class:`~orccad_app.robottask.labels.PhaseLabel` regions), so ``active(X)`` is a property of
states, and every signal the lowering adds has its role in :attr:`ApplicationLowerer.roles`. A type-2 exception raised by a task
is caught by the innermost enclosing
``try`` that names it (the task and the ``try`` body are killed, the handler runs); an
uncaught one ends the mission with status ``failed`` and the exception's name. A type-3
exception aborts the whole mission in the same instant (every task is killed), status
``aborted``; the optional ``on fatal`` block then runs to completion. ``run … within D``
raises ``Timeout`` if the task has not ended after D.
"""

from __future__ import annotations

from dataclasses import dataclass

from orccad_app.diagnostics import OrccadError, SourceLocation
from orccad_app.lang import ast
from orccad_app.reactive import derived as d
from orccad_app.reactive import ir
from orccad_app.reactive.lower import Lowerer, Scope
from orccad_app.robottask.conflicts import check_resources
from orccad_app.robottask.labels import RtLabel
from orccad_app.robottask.rta import TaskSignals, record_raisers, rta_body, task_signals
from orccad_app.robottask.run_arguments import (RunArgument, argument_signal, argument_type,
                                                runtime_arguments)
from orccad_app.robottask.signals import RoleKind, SignalRoles

__all__ = ["ApplicationLowerer", "AbstractApplicationLowerer", "RunSite", "COMPOSED", "ABSTRACT",
           "contains"]

COMPOSED, ABSTRACT = "composed", "abstract"


def contains(outer: SourceLocation, inner: SourceLocation) -> bool:
    """Is ``inner``'s start inside ``outer``'s span (same file)?"""
    if outer.file != inner.file or outer.end_line is None:
        return False
    start, end = (outer.line, outer.col), (outer.end_line, outer.end_col or 0)
    return start <= (inner.line, inner.col) <= end


@dataclass(frozen=True, eq=False)
class RunSite:
    """One ``run`` statement of a mission: the unit the checker reasons about and the mission
    layer instantiates (one Robot-Task instance per site).

    :param number: the site's number (source order, from 0): the ``site`` of its
        :class:`~orccad_app.robottask.labels.RtLabel`.
    :param robottask: the Robot-Task it runs.
    :param stmt: the ``run`` statement (arguments, location).
    :param on_fatal: the statement lies in the mission's ``on fatal`` block.
    :param arguments: its run-time arguments (evaluated when the task starts).
    """

    number: int
    robottask: ast.RobotTask
    stmt: ast.Run
    on_fatal: bool = False
    arguments: tuple[RunArgument, ...] = ()

    @property
    def task(self) -> str:
        """The Robot-Task's name."""
        return self.robottask.name

    @property
    def robot(self) -> str:
        """The robot the task runs on."""
        return self.robottask.robot

    @property
    def loc(self) -> SourceLocation:
        """The ``run`` statement's location."""
        return self.stmt.loc

    def __repr__(self) -> str:
        return f"RunSite({self.number}, {self.task} at {self.loc})"


class ApplicationLowerer(Lowerer):
    """Lowers a mission with Robot-Tasks, in the composed or the abstract view."""

    view = COMPOSED

    def __init__(self, program: ast.Program, mission: ast.Mission):
        super().__init__(program, mission)
        self.tasks = {t.name: t for t in program.robottasks}
        self.sites: list[RunSite] = []
        self.roles = SignalRoles()
        self.extra_inputs: list[ir.SignalDecl] = []
        self.extra_outputs: list[ir.SignalDecl] = []
        self.task_sigs: dict[str, TaskSignals] = {}
        self.arg_signals: dict[tuple[str, str], ir.SignalDecl] = {}
        self.outcomes: dict[str, dict[str, ir.SignalDecl]] = {}
        # abstract view: each task's synchronization pre-conditions and emitted post-conditions
        self.sync: dict[str, tuple[tuple[ir.SignalDecl, ...], tuple[ir.SignalDecl, ...]]] = {}
        self.handlers: list[dict[str, ir.TrapDecl]] = []
        loc = mission.loc
        # two exceptions in one instant: the status reports the last one (hidden signals)
        self.failed = ir.SignalDecl("_failed", ir.OUTPUT, "string", loc, combine="last")
        self.aborted = ir.SignalDecl("_aborted", ir.OUTPUT, "string", loc, combine="last")
        self.failed_trap = ir.TrapDecl("_failed", loc)
        self.fatal_trap = ir.TrapDecl("_fatal", loc)
        self.in_on_fatal = False  # lowering the 'on fatal' block (sub-missions it runs too)

    # ------------------------------------------------------------------ the mission
    def lower(self) -> ir.Program:
        check_resources(self.source, self.mission)
        loc = self.mission.loc
        body = ir.Trap(self.failed_trap, self.block(self.mission.body, self.scope), loc)
        if self.mission.on_fatal is None:
            wrapped = ir.Trap(self.fatal_trap, body, loc)
        else:
            finished = ir.TrapDecl("_finished", loc)
            self.in_on_fatal = True
            on_fatal = self.block(self.mission.on_fatal, self.scope)
            self.in_on_fatal = False
            wrapped = ir.Trap(finished, d.seq(
                ir.Trap(self.fatal_trap, d.seq(body, ir.Exit(finished, loc)), loc), on_fatal), loc)
        return ir.Program(self.mission.name, (*self.inputs, *self.extra_inputs),
                          (*self.outputs, *self.extra_outputs), wrapped, loc,
                          self.failed, self.aborted, self.relations())

    def raised_signal(self, name: str, loc: SourceLocation) -> ir.SignalDecl:
        """The output ``E.raised``, present in the instant exception ``E`` is raised."""
        decl = self.scope.signals.get(f"{name}.raised")
        if decl is None:
            decl = self._add(ir.SignalDecl(f"{name}.raised", ir.OUTPUT, None, loc))
            self.scope.signals[decl.name] = decl
            self.roles.add(decl.name, RoleKind.RAISED, name=name)
        return decl

    def raise_(self, name: str, loc: SourceLocation) -> ir.Stmt:
        """A type-2 exception: to the innermost ``catch`` of ``name``, else mission failure."""
        raised = ir.Emit(self.raised_signal(name, loc), None, loc)
        for handlers in reversed(self.handlers):
            if name in handlers:
                return d.seq(raised, ir.Exit(handlers[name], loc))
        return d.seq(raised, ir.Emit(self.failed, ir.Const(name, loc), loc),
                     ir.Exit(self.failed_trap, loc))

    def fatal(self, name: str, loc: SourceLocation) -> ir.Stmt:
        """A type-3 exception: the mission is aborted in this instant."""
        return d.seq(ir.Emit(self.raised_signal(name, loc), None, loc),
                     ir.Emit(self.aborted, ir.Const(name, loc), loc), ir.Exit(self.fatal_trap, loc))

    # ------------------------------------------------------------------ signals
    def _add(self, decl: ir.SignalDecl) -> ir.SignalDecl:
        (self.extra_inputs if decl.kind == ir.INPUT else self.extra_outputs).append(decl)
        return decl

    def global_signal(self, name: str, loc: SourceLocation, emitted: bool) -> ir.SignalDecl:
        """A synchronization pre/post-condition: a declared signal, else made implicitly."""
        decl = self.scope.signals.get(name)
        if decl is None:
            decl = self._add(ir.SignalDecl(name, ir.OUTPUT if emitted else ir.INPUT, None, loc))
            self.scope.signals[name] = decl
        elif emitted and decl.kind == ir.INPUT:
            raise OrccadError(f"post-condition '{name}' is declared as an input signal: a "
                              "Robot-Task cannot emit it", loc)
        return decl

    def signals_of(self, task: ast.RobotTask) -> TaskSignals:
        if task.name not in self.task_sigs:
            sig = task_signals(task, self.global_signal)
            for decl in (*sig.inputs, *sig.outputs):
                self._add(decl)
            sig.record(self.roles)
            self.task_sigs[task.name] = sig
        return self.task_sigs[task.name]

    def outcomes_of(self, task: ast.RobotTask) -> dict[str, ir.SignalDecl]:
        """Abstract view: ``start`` (output), ``good_end`` and the exceptions (inputs); the
        synchronization pre-conditions (inputs) and ``postcondition emit S`` (outputs) are
        the mission-level signals of the composed view (:meth:`sync_of`)."""
        if task.name not in self.outcomes:
            x, loc = task.name, task.loc
            found = {"start": self._add(ir.SignalDecl(f"{x}.start", ir.OUTPUT, None, loc)),
                     "good_end": self._add(ir.SignalDecl(f"{x}.good_end", ir.INPUT, None, loc))}
            fatal = [e.name for e in task.exceptions if e.type is ast.ExceptionType.FATAL]
            for name in (*task.raisable(), *fatal):
                found[name] = self._add(ir.SignalDecl(f"{x}.{name}", ir.INPUT, None, loc))
            self.roles.add(found["start"].name, RoleKind.START, x)
            self.roles.add(found["good_end"].name, RoleKind.GOOD_END, x)
            for name in (*task.raisable(), *fatal):
                self.roles.add(found[name].name, RoleKind.EVENT, x, name)
            record_raisers(task, self.roles)
            self.outcomes[task.name] = found
            self.sync[task.name] = (
                tuple(self.global_signal(p.signal, p.loc, False) for p in task.preconditions
                      if isinstance(p, ast.SignalPrecondition)),
                tuple(self.global_signal(p.signal, p.loc, True) for p in task.postconditions
                      if isinstance(p, ast.SignalPostcondition)))
        return self.outcomes[task.name]

    # ------------------------------------------------------------------ statements
    def _run(self, s: ast.Run, scope: Scope) -> ir.Stmt:
        task = self.tasks.get(s.task)
        if task is None:
            raise OrccadError(f"unknown Robot-Task '{s.task}'", s.task_loc or s.loc)
        if self.view == COMPOSED:  # the task's own signals first, in the declaration order
            self.signals_of(task)
        else:
            self.outcomes_of(task)
        arguments, emits = self._arguments(task, s, scope)
        site = RunSite(len(self.sites), task, s, self.in_on_fatal, arguments)
        self.sites.append(site)
        if self.view == COMPOSED:
            body = rta_body(self.signals_of(task), site.number, self.raise_, self.fatal)
        else:
            body = self._abstract_run(task, site.number, s.loc)
        body = d.seq(*emits, body)
        if s.within_ns is None:
            return body
        done = ir.TrapDecl("_within", s.loc)
        watchdog = d.seq(d.await_duration(ir.Const(s.within_ns, s.loc), s.loc),
                         self.raise_("Timeout", s.loc))
        return ir.Trap(done, ir.Par((d.seq(body, ir.Exit(done, s.loc)), watchdog), s.loc), s.loc)

    def _arguments(self, task: ast.RobotTask, s: ast.Run, scope: Scope
                   ) -> tuple[tuple[RunArgument, ...], list[ir.Stmt]]:
        """The run-time arguments of a run site, and the emissions of their values in the
        instant the task starts (the outputs ``X.arg.P``)."""
        arguments: list[RunArgument] = []
        emits: list[ir.Stmt] = []
        for param, arg in runtime_arguments(task, s):
            key = (task.name, param.name)
            decl = self.arg_signals.get(key)
            if decl is None:
                decl = self._add(ir.SignalDecl(argument_signal(*key), ir.OUTPUT,
                                               argument_type(param), param.loc))
                self.arg_signals[key] = decl
                self.roles.add(decl.name, RoleKind.ARGUMENT, task.name, param.name)
            arguments.append(RunArgument(param.name, arg.value, arg.loc, decl.name))
            emits.append(ir.Emit(decl, self.expr(arg.value, scope), arg.loc))
        return tuple(arguments), emits

    def _abstract_run(self, task: ast.RobotTask, site: int, loc: SourceLocation) -> ir.Stmt:
        """``X.start``; the synchronization pre-conditions awaited (immediately, as the RTA's
        first phase does); then the first outcome input: ``X.good_end`` emits the task's
        ``postcondition emit S`` signals in its instant (as the composed view does), an
        exception is raised."""
        signals = self.outcomes_of(task)
        pre, post = self.sync[task.name]
        ended = ir.TrapDecl("_ended", loc)

        def wait(name: str) -> ir.Stmt:
            return d.await_signal(ir.SigRef(signals[name], loc), loc=loc)

        good_end = d.seq(wait("good_end"), *(ir.Emit(s, None, loc) for s in post),
                         ir.Exit(ended, loc))
        branches = [good_end]
        branches += [d.seq(wait(e), self.raise_(e, loc)) for e in task.raisable()]
        branches += [d.seq(wait(e.name), self.fatal(e.name, loc)) for e in task.exceptions
                     if e.type is ast.ExceptionType.FATAL]
        outcome = ir.Trap(ended, ir.Par(tuple(branches), loc), loc)
        waits = [d.await_signal(ir.SigRef(s, loc), immediate=True, loc=loc) for s in pre]
        synchronized = waits[0] if len(waits) == 1 else ir.Par(tuple(waits), loc) if waits \
            else ir.Nothing(loc)
        return ir.Mark(RtLabel(task.name, site), d.seq(ir.Emit(signals["start"], None, loc),
                                                        synchronized, outcome), loc)

    def _fail(self, s: ast.Fail, scope: Scope) -> ir.Stmt:
        """``fail E;``: a type-2 exception raised by the plan itself."""
        return self.raise_(s.exception, s.loc)

    def _try(self, s: ast.Try, scope: Scope) -> ir.Stmt:
        done = ir.TrapDecl("_try_done", s.loc)
        traps = [ir.TrapDecl(f"_catch_{i}", c.loc) for i, c in enumerate(s.catches)]
        handlers: dict[str, ir.TrapDecl] = {}
        for trap, catch in zip(traps, s.catches):
            for name in catch.exceptions:
                handlers.setdefault(name, trap)  # the first catch naming it wins
        self.handlers.append(handlers)
        try:
            stmt = d.seq(self.block(s.body, scope), ir.Exit(done, s.loc))
        finally:
            self.handlers.pop()
        for trap, catch in reversed(list(zip(traps, s.catches))):
            stmt = d.seq(ir.Trap(trap, stmt, catch.loc), self.block(catch.body, scope),
                         ir.Exit(done, catch.loc))
        return ir.Trap(done, stmt, s.loc)


class AbstractApplicationLowerer(ApplicationLowerer):
    """The abstract view: Robot-Tasks as start/outcome signals (for ``orccad react``)."""

    view = ABSTRACT
