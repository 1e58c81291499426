"""The Robot-Tasks of a mission run, following the automaton's state reaction by reaction.

:class:`RobotTaskLifecycle` is the part of :class:`~orccad_app.mission.run.MissionRun` (a mixin)
that applies a reaction's new state to the run sites: the labels of the new state say which
Robot-Task instance runs and in which :class:`~orccad_app.robottask.labels.Phase` (its
:class:`~orccad_app.robottask.labels.PhaseLabel`): phase 1 runs no module, phase 2 the
measuring modules (measurement pre-conditions), phase 3 every module. Modules are activated
(``init()`` then a release now) and killed (the unfinished job aborted) to match; ``X.start`` on
a site already running restarts its modules; every run of a Robot-Task starts with fresh module
instances (nominal parameters, no state, even when the same plan is run again) and fresh ports
(its channels reset, :meth:`~orccad_app.executive.simulation.Simulation.reset_ports`). An output
whose role (:class:`~orccad_app.robottask.signals.SignalRoles`) is an adjustment of X's type-1
exception E applies E's update to the running module (computed in that instant, a ramp stepped
at the module's releases: :mod:`~orccad_app.mission.updates`; a refused value ends the run
``failed``); one whose role is a raised exception records it. Each Robot-Task run is a
:class:`~orccad_app.mission.result.RobotTaskRecord`, each exception an
:class:`~orccad_app.mission.result.ExceptionRecord`, and the mission observers' hooks are told.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any, Callable

from orccad_app.executive.simulation import Simulation
from orccad_app.lang.ast_robottask import ExceptionType
from orccad_app.mission.backend import ModuleTaskBackend
from orccad_app.mission.plan import MissionPlan, SiteModules
from orccad_app.mission.reactor import MissionReactor
from orccad_app.mission.result import ExceptionRecord, RobotTaskRecord, TaskOutcome
from orccad_app.mission.updates import TypeOneUpdates, UpdateError
from orccad_app.robottask.binding import plain_arguments
from orccad_app.robottask.labels import Phase, PhaseLabel, RtLabel
from orccad_app.robottask.signals import RoleKind, SignalRoles

__all__ = ["RobotTaskLifecycle", "site_phases"]


def site_phases(labels: Iterable[object]) -> dict[int, Phase]:
    """Site number -> phase of every Robot-Task a state's ``labels`` say is running."""
    phases: dict[int, Phase] = {}
    for label in labels:
        if isinstance(label, PhaseLabel):
            phases[label.site] = max(phases.get(label.site, label.phase), label.phase)
        elif isinstance(label, RtLabel):
            phases.setdefault(label.site, Phase.SYNCHRONIZING)
    return phases


class RobotTaskLifecycle:
    """Starts, kills, restarts and updates (type 1) the run sites' Module-Tasks as the automaton's state
    changes, and records the Robot-Task runs and the exceptions (see the module docstring).

    A mixin of :class:`~orccad_app.mission.run.MissionRun`, which sets these attributes.
    """

    plan: MissionPlan
    reactor: MissionReactor
    backend: ModuleTaskBackend
    sim: Simulation
    records: list[RobotTaskRecord]
    exceptions: list[ExceptionRecord]
    _hooks: dict[str, list[Callable[..., Any]]]
    _roles: SignalRoles
    _updates: TypeOneUpdates
    _phase: dict[int, Phase]
    _active: dict[int, set[str]]
    _running: dict[int, RobotTaskRecord]
    _adjust: dict[int, dict]

    def _phases(self) -> dict[int, Phase]:
        return site_phases(self.reactor.labels)

    def _running_site(self, task: str) -> SiteModules | None:
        for site in self.plan.sites:
            if site.task == task and self._phase.get(site.number, Phase.IDLE) is not Phase.IDLE:
                return site
        return None

    def _exceptions(self, now: int, outputs: tuple[str, ...]) -> dict[str, str | None]:
        """Record the exceptions of this reaction; return raised name -> task."""
        raised: dict[str, str | None] = {}
        for name in outputs:
            role = self._roles.get(name)
            if role is None or role.name is None:
                continue
            if role.kind is RoleKind.ADJUST and role.task is not None:
                site = self._running_site(role.task)
                update = (self._adjust.get(site.number, site.adjustments).get(role.name)
                          if site is not None else None)
                try:
                    change = None if update is None else \
                        self._updates.apply(update, role.name, now)
                except UpdateError:  # the exception happened; its update ends the run
                    self._record(ExceptionRecord(now, role.name, ExceptionType.ADJUST, role.task))
                    raise
                self._record(ExceptionRecord(now, role.name, ExceptionType.ADJUST, role.task, change))
            elif role.kind is RoleKind.RAISED:
                kind, task = self._origin(role.name)
                raised[role.name] = task
                self._record(ExceptionRecord(now, role.name, kind, task))
        return raised

    def _origin(self, exception: str) -> tuple[ExceptionType, str | None]:
        """The type of ``exception`` and the running task that raised it (``None`` and type 2
        for the mission's own ``Timeout``)."""
        raisers = {r.task: r.type for r in self._roles.raisers.get(exception, ())}
        for site in self.plan.sites:
            if self._phase.get(site.number, Phase.IDLE) is not Phase.IDLE and \
                    site.task in raisers:
                return raisers[site.task], site.task
        return ExceptionType.ABORT, None

    def _record(self, record: ExceptionRecord) -> None:
        self.exceptions.append(record)
        for hook in self._hooks["on_exception"]:
            hook(record)

    def _update_sites(self, now: int, emitted: set[str], raised: dict[str, str | None],
                      phases: dict[int, Phase], values: dict[str, Any]) -> None:
        for site in self.plan.sites:
            number = site.number
            old = self._phase.get(number, Phase.IDLE)
            new = phases.get(number, Phase.IDLE)
            restart = old > 0 and new > 0 and site.start_signal in emitted
            if old > 0 and (new == 0 or restart):
                self._end_task(now, site, _outcome(site, emitted, raised))
            starting = new > 0 and (old == 0 or restart)
            if starting:
                self._start_task(now, site, values)
            active = self._active[number]
            wanted = site.wanted(new)
            stop = [m for m in site.modules if m in active and (restart or m not in wanted)]
            if stop:
                self.backend.kill(stop, now)
                active.difference_update(stop)
            if starting:  # fresh ports: nothing the previous run wrote is read again
                self.backend.reset_ports(site.modules, now)
            start = [m for m in wanted if m not in active]
            if start:
                self.backend.activate(start, now)
                self._updates.activated(start, now)
                active.update(start)
        self._phase = phases

    def _start_task(self, now: int, site: SiteModules, values: dict[str, Any]) -> None:
        instance = site.bound(values)  # the run-time arguments' values, checked
        for name, compute in site.fresh_computes(instance).items():  # no state, no update
            self.sim.replace_compute(name, compute)
        self._adjust[site.number] = site.adjustments_of(instance)
        args = plain_arguments(instance.params)
        record = RobotTaskRecord(site.task, site.number, now, error_unit=site.error_unit,
                                 args=args)
        self._running[site.number] = record
        self.records.append(record)
        for hook in self._hooks["on_task_start"]:
            hook(now, site.task, site.number, args)

    def _end_task(self, now: int, site: SiteModules,
                  outcome: tuple[TaskOutcome, str | None]) -> None:
        self._updates.stop(site.modules)
        record = self._running.pop(site.number)
        record.end_ns = now
        record.end, record.exception = outcome
        for hook in self._hooks["on_task_end"]:
            hook(now, site.task, site.number, record.outcome)


def _outcome(site: SiteModules, emitted: set[str],
             raised: dict[str, str | None]) -> tuple[TaskOutcome, str | None]:
    """How the run of ``site`` ended, and the exception that ended it if one did."""
    if site.good_end_signal in emitted:
        return TaskOutcome.GOOD_END, None
    for exception, origin in raised.items():
        if origin == site.task:
            return TaskOutcome.RAISED, exception
    if "Timeout" in raised:
        return TaskOutcome.RAISED, "Timeout"
    return TaskOutcome.KILLED, None
