"""Generation of a Robot-Task's behaviour automaton (RTA), RR-1801 §3.4.3.

The RTA is never written by hand: it is generated as kernel IR from the ``robottask`` block,
in the paper's three phases::

    phase 1   await every synchronization pre-condition (in parallel);  emit X.measure
    phase 2   await every measurement pre-condition (in parallel, each under its
              watchdog);                                                  emit X.activate
    phase 3   trap HAPPY_END {
                  every type-1 exception E: emit X.E.adjust, the task goes on
               || each type-2 exception E: raise E to the application (the RT is killed)
               || each type-3 exception F: abort the application
               || await every measurement post-condition; exit HAPPY_END
               || await the nominal duration T; exit HAPPY_END
              }
              emit X.good_end and every synchronization post-condition

Interface of the RTA of a task ``X`` (documented in ``docs/robot-tasks.md``):

- inputs: the synchronization pre-conditions (mission-level signals), ``X.<observer>`` for
  each measurement pre- or post-condition (the observer's event), ``X.<E>`` for each
  exception (the event of the observer that raises it);
- outputs: ``X.start`` (the task is started), ``X.measure`` (activate the measuring modules),
  ``X.activate`` (activate all modules), ``X.<E>.adjust`` (apply the type-1 parameter
  update of E), ``X.good_end`` and the synchronization post-conditions.

A measurement pre-condition's watchdog expiring raises ``<observer>_timeout`` (type 2).
How an exception reaches the application is given by the caller (``raise_``/``fatal``), so
the same generator serves the stand-alone RTA (``orccad rta``) and its instances inlined at
each ``run`` of a mission. Each instance is a marked region labelled
:class:`~orccad_app.robottask.labels.RtLabel` with phase regions
:class:`~orccad_app.robottask.labels.PhaseLabel`, so every state of the compiled automaton
tells which Robot-Task is active and in which :class:`~orccad_app.robottask.labels.Phase`.
The role of each signal made here is recorded in a
:class:`~orccad_app.robottask.signals.SignalRoles` (:meth:`TaskSignals.record`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

from orccad_app.diagnostics import OrccadError, SourceLocation
from orccad_app.lang import ast
from orccad_app.reactive import derived as d
from orccad_app.reactive import ir
from orccad_app.robottask.labels import Phase, PhaseLabel, RtLabel
from orccad_app.robottask.signals import RoleKind, SignalRoles

__all__ = ["TaskSignals", "task_signals", "rta_body", "rta_program", "Raise", "record_raisers"]

#: ``raise_(exception_name, location) -> statement`` reports an exception to the application.
Raise = Callable[[str, SourceLocation], ir.Stmt]


@dataclass
class TaskSignals:
    """The signals of one Robot-Task's RTA, made once per task and program."""

    task: ast.RobotTask
    start: ir.SignalDecl
    measure: ir.SignalDecl
    activate: ir.SignalDecl
    good_end: ir.SignalDecl
    events: dict[str, ir.SignalDecl] = field(default_factory=dict)   # observer / exception
    adjusts: dict[str, ir.SignalDecl] = field(default_factory=dict)  # type-1 exceptions
    sync_pre: tuple[ir.SignalDecl, ...] = ()
    sync_post: tuple[ir.SignalDecl, ...] = ()

    @property
    def inputs(self) -> tuple[ir.SignalDecl, ...]:
        return tuple(self.events.values())

    @property
    def outputs(self) -> tuple[ir.SignalDecl, ...]:
        return (self.start, self.measure, self.activate, *self.adjusts.values(), self.good_end)

    def record(self, roles: SignalRoles) -> None:
        """Record the role of each of these signals (and what the task can raise)."""
        x = self.task.name
        roles.add(self.start.name, RoleKind.START, x)
        roles.add(self.measure.name, RoleKind.MEASURE, x)
        roles.add(self.activate.name, RoleKind.ACTIVATE, x)
        roles.add(self.good_end.name, RoleKind.GOOD_END, x)
        for event, decl in self.events.items():
            roles.add(decl.name, RoleKind.EVENT, x, event)
        for exception, decl in self.adjusts.items():
            roles.add(decl.name, RoleKind.ADJUST, x, exception)
        record_raisers(self.task, roles)


def record_raisers(task: ast.RobotTask, roles: SignalRoles) -> None:
    """Record the exceptions a run of ``task`` can raise into the application: its type-2
    ones (with the watchdogs' ``OBSERVER_timeout``) and its type-3 ones."""
    for name in task.raisable():
        roles.add_raiser(name, task.name, ast.ExceptionType.ABORT)
    for exc in task.exceptions:
        if exc.type is ast.ExceptionType.FATAL:
            roles.add_raiser(exc.name, task.name, ast.ExceptionType.FATAL)


def _out(name: str, loc: SourceLocation) -> ir.SignalDecl:
    return ir.SignalDecl(name, ir.OUTPUT, None, loc)


def _event(signals: TaskSignals, name: str, loc: SourceLocation) -> ir.SignalDecl:
    full = f"{signals.task.name}.{name}"
    if name in signals.events:
        raise OrccadError(f"Robot-Task {signals.task.name}: '{name}' names two events "
                          f"(two conditions or exceptions on the same observer); give the "
                          "second one its own module", loc)
    signals.events[name] = ir.SignalDecl(full, ir.INPUT, None, loc)
    return signals.events[name]


def task_signals(task: ast.RobotTask,
                 global_signal: Callable[[str, SourceLocation, bool], ir.SignalDecl]
                 ) -> TaskSignals:
    """Make the RTA's signals; ``global_signal(name, loc, emitted)`` resolves the
    synchronization pre/post-conditions, which are mission-level signals."""
    x, loc = task.name, task.loc
    signals = TaskSignals(task, _out(f"{x}.start", loc), _out(f"{x}.measure", loc),
                          _out(f"{x}.activate", loc), _out(f"{x}.good_end", loc))
    for pre in task.preconditions:
        if isinstance(pre, ast.MeasurePrecondition):
            _event(signals, pre.observer.func, pre.loc)
    for exc in task.exceptions:
        _event(signals, exc.name, exc.loc)
        if exc.type is ast.ExceptionType.ADJUST:
            signals.adjusts[exc.name] = _out(f"{x}.{exc.name}.adjust", exc.loc)
    for post in task.postconditions:
        if isinstance(post, ast.MeasurePostcondition):
            _event(signals, post.observer.func, post.loc)
    signals.sync_pre = tuple(global_signal(p.signal, p.loc, False) for p in task.preconditions
                             if isinstance(p, ast.SignalPrecondition))
    signals.sync_post = tuple(global_signal(p.signal, p.loc, True) for p in task.postconditions
                              if isinstance(p, ast.SignalPostcondition))
    return signals


def _all(branches: list[ir.Stmt], loc: SourceLocation) -> ir.Stmt:
    if not branches:
        return ir.Nothing(loc)
    return branches[0] if len(branches) == 1 else ir.Par(tuple(branches), loc)


def _await(signal: ir.SignalDecl, loc: SourceLocation, immediate: bool = False) -> ir.Stmt:
    return d.await_signal(ir.SigRef(signal, loc), immediate=immediate, loc=loc)


def _phase2(sig: TaskSignals, raise_: Raise) -> ir.Stmt:
    waits = []
    for pre in sig.task.preconditions:
        if not isinstance(pre, ast.MeasurePrecondition):
            continue
        wait = _await(sig.events[pre.observer.func], pre.loc)
        if pre.within_ns is not None:
            _, start, expired = d.deadline(ir.Const(pre.within_ns, pre.loc), pre.loc, "_watchdog")
            timeout = raise_(f"{pre.observer.func}_timeout", pre.loc)
            wait = d.seq(start, d.abort(wait, expired, handler=timeout, loc=pre.loc))
        waits.append(wait)
    return _all(waits, sig.task.loc)


def _phase3(sig: TaskSignals, raise_: Raise, fatal: Raise) -> ir.Stmt:
    task, loc = sig.task, sig.task.loc
    happy = ir.TrapDecl("HAPPY_END", loc)
    branches: list[ir.Stmt] = []
    for exc in task.exceptions:
        event = sig.events[exc.name]
        if exc.type is ast.ExceptionType.ADJUST:
            branches.append(ir.Loop(d.seq(_await(event, exc.loc),
                                          ir.Emit(sig.adjusts[exc.name], None, exc.loc)),
                                    exc.loc, "type-1 exception"))
        elif exc.type is ast.ExceptionType.ABORT:
            branches.append(d.seq(_await(event, exc.loc), raise_(exc.name, exc.loc)))
        else:
            branches.append(d.seq(_await(event, exc.loc), fatal(exc.name, exc.loc)))
    posts = [_await(sig.events[p.observer.func], p.loc) for p in task.postconditions
             if isinstance(p, ast.MeasurePostcondition)]
    if posts:
        branches.append(d.seq(_all(posts, loc), ir.Exit(happy, loc)))
    if task.duration_ns is not None:
        branches.append(d.seq(d.await_duration(ir.Const(task.duration_ns, loc), loc),
                              ir.Exit(happy, loc)))
    if not posts and task.duration_ns is None:
        branches.append(d.halt(loc))  # no good end: runs until killed or an exception
    return ir.Trap(happy, _all(branches, loc), loc)


def rta_body(sig: TaskSignals, site: int, raise_: Raise, fatal: Raise) -> ir.Stmt:
    """One instance of the RTA, marked :class:`RtLabel` with its three :class:`PhaseLabel`
    regions."""
    task, loc = sig.task, sig.task.loc
    phase1 = _all([_await(s, loc, immediate=True) for s in sig.sync_pre], loc)
    good_end = [ir.Emit(sig.good_end, None, loc)] + [ir.Emit(s, None, loc) for s in sig.sync_post]
    body = d.seq(
        ir.Emit(sig.start, None, loc),
        ir.Mark(PhaseLabel(task.name, site, Phase.SYNCHRONIZING), phase1, loc),
        ir.Emit(sig.measure, None, loc),
        ir.Mark(PhaseLabel(task.name, site, Phase.MEASURING), _phase2(sig, raise_), loc),
        ir.Emit(sig.activate, None, loc),
        ir.Mark(PhaseLabel(task.name, site, Phase.ACTIVE), _phase3(sig, raise_, fatal), loc),
        *good_end)
    return ir.Mark(RtLabel(task.name, site), body, loc)


def rta_program(task: ast.RobotTask, declared: dict[str, ir.SignalDecl] | None = None
                ) -> ir.Program:
    """The stand-alone RTA of ``task``, started in its first instant.

    A type-2 exception ends it with status ``failed`` and a type-3 one with ``aborted`` (the
    reason is the exception's name); the good end with ``done``.
    """
    declared = dict(declared or {})
    extra_inputs: list[ir.SignalDecl] = []
    extra_outputs: list[ir.SignalDecl] = []

    def global_signal(name: str, loc: SourceLocation, emitted: bool) -> ir.SignalDecl:
        if name not in declared:
            decl = ir.SignalDecl(name, ir.OUTPUT if emitted else ir.INPUT, None, loc)
            declared[name] = decl
            (extra_outputs if emitted else extra_inputs).append(decl)
        return declared[name]

    sig = task_signals(task, global_signal)
    failed = ir.SignalDecl("_failed", ir.OUTPUT, "string", task.loc)
    aborted = ir.SignalDecl("_aborted", ir.OUTPUT, "string", task.loc)
    stop = ir.TrapDecl("_stop", task.loc)

    def ending(status: ir.SignalDecl) -> Raise:
        return lambda name, loc: d.seq(ir.Emit(status, ir.Const(name, loc), loc), ir.Exit(stop, loc))

    body = ir.Trap(stop, rta_body(sig, 0, ending(failed), ending(aborted)), task.loc)
    return ir.Program(f"{task.name}.rta", (*extra_inputs, *sig.inputs),
                      (*sig.outputs, *extra_outputs), body, task.loc, failed, aborted)
