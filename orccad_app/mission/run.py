"""A mission in the loop: the application automaton and the RTAs drive the executive.

:class:`MissionRun` couples a :class:`~orccad_app.mission.plan.MissionPlan` (the
composed automaton, one TCS for every ``run`` site, the plants) to a
:class:`~orccad_app.executive.simulation.Simulation` (docs/design.md, *Reactions*):

**When the automaton reacts.** Observers' events (a written event port ``X.module.event`` is the
automaton input ``X.E``), injected inputs (``--inject SIG@T``) and timers are signals. The
automaton reacts, in zero time, at every instant where one of them can matter:

- at every instant with an observer event or an injection (all of the instant's signals in one
  reaction, after the jobs finishing then have written their outputs); an observer's event
  first goes to its Robot-Task's automaton processor (``automaton on P reaction D``: over the
  bus from another processor, then a reaction job of ``D`` there,
  :mod:`orccad_app.executive.reaction`);
- on a periodic *tick* (default: the gcd of the module periods, 1 ms for the arm missions),
  because timers (``await 2 s``, a task's ``duration``, watchdogs, ``within``) are data tests
  on the clock: a deadline is seen at the first tick at or after it — exactly at it when it is a
  multiple of the tick. A reaction costs about a microsecond, so ticking is cheaper than
  finding the next deadline in the automaton's data tests, and it is always correct.

Reactions are events of class ``CONTROL``: a reaction at ``t`` sees the outputs of jobs that
finished at ``t`` and its activations release at ``t``.

**What a reaction does.** From the labels of the new state, the Robot-Tasks' Module-Tasks are
activated, killed, restarted (fresh module instances and ports) and updated (type-1 parameter updates),
and the raised exceptions recorded: :mod:`~orccad_app.mission.lifecycle`. The run stops when
the mission terminates (after an ``on fatal`` block), at ``until_ns`` (status ``timeout``; its
default and the run's cost budget: :mod:`~orccad_app.mission.budget`), on a run-time failure
(deadlock, diverging plant, failing module: ``failed``) or on Ctrl-C (``aborted``).

**Plant extensions and faults.** A robot type whose ``plant_extension()`` returns a
:class:`~orccad_app.control.plant_extension.PlantExtension` gets it attached to its plant
(extra physics, sensor ports, named faults). ``--inject ROBOT.FAULT=VALUE@T`` (``auv.leak=1@120``,
``auv.battery=5%@60``: a trailing ``%`` is dropped, the fault's unit applies) applies the fault
``FAULT`` of robot ``ROBOT``'s plant at ``T`` seconds instead of raising a signal.

**Where the jobs run.** The run's :class:`~orccad_app.mission.backend.ModuleTaskBackend`
(a constructor argument) says where the Module-Tasks' jobs compute and what steps the
automaton: in this process (:class:`~orccad_app.mission.backend.InProcess`, the default), or
in the controller process of ``orccad sil``, in lockstep or in real time. The run activates,
kills and resets Module-Tasks, hands inputs and holds its events through it.

**Observers.** Executive observers are passed to the simulation; those that also define the
mission's callbacks (:class:`~orccad_app.mission.observer.MissionObserver`) get those too
(traces).
"""

from __future__ import annotations

import time
from typing import Any, Iterable

from orccad_app.control.ports import TASK_ERROR
from orccad_app.diagnostics import OrccadError
from orccad_app.executive.bus import Bus
from orccad_app.executive.deadlock import DeadlockError
from orccad_app.executive.delays import ControllerDelays
from orccad_app.executive.kernel import EventClass
from orccad_app.executive.observer import Observer
from orccad_app.executive.plant import MujocoPlant, PlantDivergenceError
from orccad_app.executive.processor import Processor
from orccad_app.executive.simulation import Simulation
from orccad_app.executive.task_runtime import ComputeError
from orccad_app.mission.backend import InProcess, ModuleTaskBackend
from orccad_app.mission.budget import DEFAULT_UNTIL_NS, check_run_budget
from orccad_app.mission.injection import Injection, PlantFault, typed_injection
from orccad_app.mission.lifecycle import RobotTaskLifecycle
from orccad_app.mission.reactor import MissionReactor
from orccad_app.mission.observer import MISSION_HOOKS
from orccad_app.mission.plan import MissionPlan
from orccad_app.mission.result import ExceptionRecord, MissionStatus, RobotTaskRecord, RunResult
from orccad_app.mission.updates import TypeOneUpdates, UpdateError
from orccad_app.reactive.status import at_horizon
from orccad_app.robottask.binding import ArgumentError
from orccad_app.robottask.labels import Phase

__all__ = ["MissionRun", "MissionReactor", "Terminated", "INTERRUPTED", "TERMINATED"]

_CONTROL = EventClass.CONTROL
INTERRUPTED = _INTERRUPTED = "interrupted (Ctrl-C)"
TERMINATED = _TERMINATED = "interrupted (SIGTERM)"


class Terminated(KeyboardInterrupt):
    """Raised in the main thread by ``orccad run``'s SIGTERM handler (a ``kill``, a CI
    timeout): the run ends like after Ctrl-C, with its report and a complete trace."""
_NO_INPUTS: frozenset[str] = frozenset()


class ReactionError(OrccadError):
    """A run-time error of the automaton (a value read before it was ever emitted, an
    overflow…), located in the mission: the run ends ``failed``."""


_RUN_FAILURES = (DeadlockError, PlantDivergenceError, ComputeError, UpdateError)
_LOCATED_FAILURES = (ArgumentError, ReactionError)


class _Link(Observer):
    """Forwards the executive's signals and ``e`` writes to the mission run."""

    def __init__(self, run: MissionRun) -> None:
        self._run = run

    def on_signal(self, t_ns: int, name: str, value: Any) -> None:
        self._run.signal(name, value)

    def on_write(self, t_ns: int, module: str, port: str, value: Any) -> None:
        if port == TASK_ERROR:
            self._run.task_error(module, value)

    def wants_write(self, module: str, port: str) -> bool:
        return port == TASK_ERROR


class MissionRun(RobotTaskLifecycle):
    """One run of a planned mission. See the module docstring.

    :param plan: the mission's plan (:func:`~orccad_app.mission.plan.plan_mission`).
    :param seed: the run's seed (execution times drawn in ``[bcet, wcet]``, sensor noise).
    :param until_ns: the simulated-time limit [ns].
    :param injections: inputs raised at given instants.
    :param processors: processor descriptions (scheduler, context switch); others default.
    :param bus: the bus between processors.
    :param observers: executive observers (traces), optionally with the mission hooks.
    :param realtime: ``None`` (as fast as possible) or the pacing factor (sim s / wall s).
    :param tick_ns: the automaton's periodic reaction [ns] (default ``plan.tick_ns``).
    :param backend: where the Module-Tasks' jobs run and what steps the automaton (default
        :class:`~orccad_app.mission.backend.InProcess`: this process, the Python reactor);
        its pacing, when it has one, replaces ``realtime``.
    :param delays: the exchange delay and release jitter a real controller adds
        (:mod:`orccad_app.executive.delays`; default none: the ideal exchange).
    """

    def __init__(self, plan: MissionPlan, *, seed: int = 0,
                 until_ns: int = DEFAULT_UNTIL_NS, injections: Iterable[Injection] = (),
                 processors: Iterable[Processor] = (), bus: Bus | None = None,
                 observers: Iterable[Any] = (), realtime: float | None = None,
                 tick_ns: int | None = None, backend: ModuleTaskBackend | None = None,
                 delays: ControllerDelays = ControllerDelays()) -> None:
        if not isinstance(until_ns, int) or until_ns <= 0:
            raise OrccadError(f"--until must be > 0 s, got {until_ns!r} ns")
        self.backend: ModuleTaskBackend = backend if backend is not None else InProcess()
        plan = self.backend.run_plan(plan)
        self.plan = plan
        self.seed = seed
        self.until_ns = until_ns
        check_run_budget(plan, until_ns)
        self.realtime = realtime if self.backend.pacing is None else self.backend.pacing
        self.tick_ns = tick_ns or plan.tick_ns
        self.reactor: MissionReactor = self.backend.reactor(plan)
        observers = list(observers)
        self._hooks = {hook: [getattr(o, hook) for o in observers if hasattr(o, hook)]
                       for hook in MISSION_HOOKS}
        self._on_reaction = self._hooks["on_reaction"]
        plants: list[MujocoPlant] = [spec.build() for spec in plan.plants]
        self.sim = Simulation(plan.tcs, seed=seed, processors=processors, bus=bus,
                              plants=plants, observers=[_Link(self), *observers],
                              delays=delays)
        self.kernel = self.sim.kernel
        self._updates = TypeOneUpdates(self.kernel, plan.tcs, self.sim.hooks.on_param)
        self._signals = plan.signals
        self._roles = plan.roles
        self._error_site = {s.error_module: s.number for s in plan.sites if s.error_module}
        self._outputs = {s.name for s in plan.automaton.outputs if plan.roles.get(s.name) is None}
        self._pending: dict[str, Any] = {}
        self._queued = False  # a reaction event is in the kernel's queue
        self._reacted_at = -1
        self._state: int | None = None
        self._phase: dict[int, Phase] = {}
        self._active: dict[int, set[str]] = {s.number: set() for s in plan.sites}
        self._running: dict[int, RobotTaskRecord] = {}
        self._adjust: dict[int, dict] = {}  # site -> type-1 updates of its current start
        self.records: list[RobotTaskRecord] = []
        self.exceptions: list[ExceptionRecord] = []
        self.outputs: list[tuple[int, str, Any]] = []
        self._stopped_by: str | None = None
        self._route_signals()
        self._schedule_inputs(injections)
        self.backend.attach(self, self.sim)

    def add_observer(self, observer: Any) -> None:
        """Observe the run from now on (executive callbacks and the mission hooks it has)."""
        self.sim.add_observer(observer)
        for hook in MISSION_HOOKS:
            if hasattr(observer, hook):
                self._hooks[hook].append(getattr(observer, hook))

    def _schedule_inputs(self, injections: Iterable[Injection]) -> None:
        inputs = {s.name: s for s in self.plan.automaton.inputs}
        for injection in injections:
            if injection.fault is not None:
                self._schedule_fault(injection, injection.fault)
                continue
            if injection.name not in inputs:
                known = ", ".join(sorted(inputs)) or "none"
                raise OrccadError(f"--inject {injection.name}: not an input of mission "
                                  f"'{self.plan.name}' (inputs: {known})")
            injection = typed_injection(injection, inputs[injection.name])
            if injection.time_ns >= self.until_ns:
                raise OrccadError(f"--inject {injection.name}@{injection.time_ns / 1e9:g}: "
                                  f"after --until ({self.until_ns / 1e9:g} s)")
            self.kernel.schedule(max(0, injection.time_ns - self.backend.input_lead_ns),
                                 _CONTROL, self._inject, injection)
        if self.backend.reacts_on_ticks:
            self.kernel.schedule(0, _CONTROL, self._tick)

    def _schedule_fault(self, injection: Injection, plant_fault: PlantFault) -> None:
        robot, fault = plant_fault.robot, plant_fault.fault
        plant = self.sim.plants.get(robot)
        if plant is None:
            raise OrccadError(f"--inject {injection.name}: no robot '{robot}' in mission "
                              f"'{self.plan.name}' (robots: {', '.join(self.sim.plants)})")
        faults = plant.extension.faults if plant.extension is not None else {}
        if fault not in faults:
            raise OrccadError(f"--inject {injection.name}: robot '{robot}' has no fault "
                              f"'{fault}' (faults: {', '.join(faults) or 'none'})")
        try:
            plant.extension.check_fault(fault, injection.value)
        except OrccadError as error:
            raise OrccadError(f"--inject {injection.name}={injection.value!r}: robot "
                              f"'{robot}': {error.message}") from None
        if injection.time_ns >= self.until_ns:
            raise OrccadError(f"--inject {injection.name}@{injection.time_ns / 1e9:g}: "
                              f"after --until ({self.until_ns / 1e9:g} s)")
        self.kernel.schedule(injection.time_ns, _CONTROL,
                             lambda _: plant.inject(fault, injection.value))

    # -- signals into the automaton ----------------------------------------------------------

    def _route_signals(self) -> None:
        """Each site's observer signals go to its automaton's processor: over the bus from
        another processor, then through a reaction of the declared time there
        (:mod:`orccad_app.executive.reaction`)."""
        servers = {}
        for site in self.plan.sites:
            key = (site.automaton_processor, site.reaction_ns)
            if key not in servers:
                servers[key] = self.sim.reaction_server(*key, self._react_to)
            for signal, name in site.events.items():
                observer = self.sim.tasks[site.event_ports[name].module].task
                self.sim.signal_routes.add(signal, observer.processor, servers[key])

    def _react_to(self, signals: list[tuple[str, Any]]) -> None:
        for name, _ in signals:
            self._post(self._signals[name], None)

    def signal(self, name: str, value: Any) -> None:
        """An executive signal: forwarded to the automaton when it is one of its inputs
        (through its route: the bus, the reaction time)."""
        target = self._signals.get(name)
        if target is not None and not self.sim.signal_routes.send(name, value):
            self._post(target, None)

    def _post(self, name: str, value: Any) -> None:
        now = self.kernel.now
        if self.backend.take_input(name, value, now):
            return
        self._pending[name] = value
        if not self._queued:
            self._queued = True
            self.kernel.schedule(now, _CONTROL, self._queued_reaction)

    def inject(self, name: str, value: Any = None) -> None:
        """Raise the automaton input ``name`` now (from an observer's callback, i.e. on the
        executive's thread): it reacts in the current instant, after the current event."""
        if name not in {s.name for s in self.plan.automaton.inputs}:
            raise OrccadError(f"{name}: not an input of mission '{self.plan.name}'")
        self._post(name, value)

    # -- what observers read and do (they never reach into the executive's Simulation) ----

    @property
    def plants(self) -> dict[str, MujocoPlant]:
        """Robot name -> its plant (read its true state: ``observe``, ``qpos``…)."""
        return self.sim.plants

    def faults(self) -> dict[str, str]:
        """Every plant fault ``ROBOT.FAULT`` the run can apply -> its description."""
        found: dict[str, str] = {}
        for robot, plant in self.sim.plants.items():
            extension = plant.extension
            faults = getattr(extension, "faults", None) or {}
            found.update({f"{robot}.{fault}": text for fault, text in faults.items()})
        return found

    def check_fault(self, robot: str, fault: str, value: Any) -> None:
        """Refuse (:class:`OrccadError`) a fault the robot's plant does not have, or a value
        out of its declared range, before it is due."""
        plant = self.sim.plants.get(robot)
        if plant is None or plant.extension is None:
            raise OrccadError(f"fault {robot}.{fault}: robot '{robot}' has no faults")
        plant.extension.check_fault(fault, value)

    def apply_fault(self, robot: str, fault: str, value: Any) -> None:
        """Apply a plant fault now (from an observer's callback)."""
        self.sim.plants[robot].inject(fault, value)

    def processor_busy_ns(self) -> dict[str, int]:
        """Processor -> its busy time so far [ns] (context switches included)."""
        return {name: processor.stats.busy_ns for name, processor in self.sim.processors.items()}

    def missed_jobs(self) -> dict[str, int]:
        """Module-Task -> its jobs so far that finished after their deadline or whose release
        was skipped (an overrun)."""
        return {name: runtime.stats.late + runtime.stats.overruns
                for name, runtime in self.sim.tasks.items()}

    @property
    def stopping(self) -> bool:
        """:meth:`abort` was called: the run ends after the current event."""
        return self._stopped_by is not None

    def abort(self, reason: str = "stopped by the user") -> None:
        """End the run after the current event with status ``aborted`` (from a callback)."""
        self._stopped_by = reason
        self.kernel.stop()

    @property
    def phases(self) -> dict[int, Phase]:
        """Site number -> phase of every running Robot-Task (a copy)."""
        return dict(self._phase)

    def warn(self, source: str, message: str) -> None:
        """Tell the observers (``on_warning``) what went wrong while the run goes on."""
        for hook in self._hooks["on_warning"]:
            hook(self.kernel.now, source, message)

    def _inject(self, injection: Injection) -> None:
        if not self.backend.take_input(injection.name, injection.value, injection.time_ns):
            self._post(injection.name, injection.value)

    def _queued_reaction(self, _: object) -> None:
        self._queued = False
        self._react(None)

    def _tick(self, _: object) -> None:
        self.kernel.schedule(self.kernel.now + self.tick_ns, _CONTROL, self._tick)
        self._react(None)

    def task_error(self, module: str, value: Any) -> None:
        """A control law wrote its task error ``e``: a tracking-error sample of its run."""
        record = self._running.get(self._error_site.get(module, -1))
        if record is not None:
            record.errors.add(value)

    # -- reactions ---------------------------------------------------------------------------

    def _react(self, _: object) -> None:
        now = self.kernel.now
        pending = self._pending
        inputs: Any
        if not pending:
            if self._reacted_at == now:
                return
            inputs = _NO_INPUTS  # a tick: no dict or set to build
        else:
            self._pending = {}
            if any(value is not None for value in pending.values()):
                inputs = pending
            else:
                inputs = set(pending)
        self._reacted_at = now
        reactor = self.reactor
        try:
            step = reactor.step(inputs, now)  # the lean path: the leaf's precomputed result
        except OrccadError as error:
            raise ReactionError(error.message, error.location, error.notes) from None
        self.apply_reaction(now, tuple(pending), step)

    def apply_reaction(self, now: int, inputs: tuple[str, ...], step: Any) -> None:
        """What the reaction at ``now`` to ``inputs`` decided (``step``, the reactor having
        made it): the hooks, the outputs, the exceptions, the Robot-Tasks started, killed and
        updated; the run stops when the mission has ended."""
        reactor = self.reactor
        for hook in self._on_reaction:
            hook(now, inputs, step.outputs, reactor.status)
        if not step.outputs and reactor.state == self._state and not reactor.finished:
            return  # a tick that changed nothing (the common case)
        emitted = set(step.outputs)
        values = reactor.values(step) if step.valued else {}
        for name in step.outputs:
            if name in self._outputs:
                self.outputs.append((now, name, values.get(name)))
        raised = self._exceptions(now, step.outputs)
        changed = self.reactor.state != self._state
        if changed:
            self._state = self.reactor.state
            phases = self._phases()
        else:
            phases = self._phase
        self._update_sites(now, emitted, raised, phases, values)
        if changed:
            for hook in self._hooks["on_state"]:
                hook(now, self.reactor.state, phases)
        if self.reactor.finished:
            self.kernel.stop()

    # -- running -----------------------------------------------------------------------------

    def run(self) -> RunResult:
        """Run until the mission ends, ``until_ns``, a run-time failure or Ctrl-C."""
        wall_start = time.perf_counter()
        status: MissionStatus | None = None
        reason: str | None = None
        try:  # aborted before it started (Ctrl-C while waiting for Foxglove): no event runs
            until_ns = self.kernel.now if self._stopped_by is not None else self.until_ns
            with self.backend.running():
                self.sim.run(until_ns, realtime=self.realtime)
        except _RUN_FAILURES as error:
            status, reason = MissionStatus.FAILED, error.message
        except _LOCATED_FAILURES as error:
            where = f"{error.location}: " if error.location is not None else ""
            status, reason = MissionStatus.FAILED, where + error.message
        except KeyboardInterrupt as interrupt:
            status = MissionStatus.ABORTED
            reason = _TERMINATED if isinstance(interrupt, Terminated) else _INTERRUPTED
        wall = time.perf_counter() - wall_start
        if status is None and self._stopped_by is not None and not self.reactor.finished:
            status, reason = MissionStatus.ABORTED, self._stopped_by
        if status is None:
            status, reason = self._final_status()
        stats = self.sim.stats()
        return self.backend.finish(RunResult(
            self.plan.name, status, reason, self.kernel.now, wall, self.records,
            self.exceptions, stats, self.plan.tcs.modules, self.outputs,
            self.sim.lateness_s if self.realtime else None, self.seed,
            interrupted=reason in (_INTERRUPTED, _TERMINATED)))

    def _final_status(self) -> tuple[MissionStatus, str | None]:
        reactor = self.reactor
        status = at_horizon(reactor.status, reactor.finished)
        if status is MissionStatus.TIMEOUT:
            return status, f"the mission was still running at {self.until_ns / 1e9:g} s"
        return status, reactor.reason
