"""Real-time software-in-the-loop: the Module-Tasks on real periodic threads.

``orccad sil FILE --realtime``: the controller process (``orccad_app/sil/c/orccad_rt.c``) runs
one thread per processor, releasing the active Module-Tasks with
``clock_nanosleep(TIMER_ABSTIME)`` at their periods on the wall clock, under ``SCHED_FIFO``
where permitted. The mission's automaton is a task of the controller too
(``orccad_rt_automaton.c``): it reacts at its ticks and at its observers' events, and records
each reaction in the shared memory. This process is the **plant server and the mission's
supervisor**: the run's :class:`RealtimeBackend` paces the executive's kernel to the wall
clock, which runs the MuJoCo plant but no Module-Task job and no reaction: every
``exchange_ns`` it brings the plant to now, writes the robot's sensors into the shared memory
(:mod:`.shared`), applies the torques the controller wrote, and applies, in order, the
reactions the automaton task recorded (:meth:`~orccad_app.mission.backend.RunHost.
apply_reaction`: start, kill, type-1 updates, fresh ports go to the controller over the
socket); an input (``--inject``) goes to the automaton task as ``OP_INPUT`` with its
instant. The outputs of the controller's last jobs go to the executive's write listeners (the
trace, the task errors of the report); while a trace listens, each job's measured life cycle
(a ring in the shared memory) goes to the observers' job callbacks (:mod:`.job_trace`).
Measured per Module-Task: releases, release lateness, overruns, deadline misses, response
times. The heartbeat is a ``PING`` every 100 ms of the run.

Every connection runs its protocol on the controller's threads (``orccad_port.c``: the 8 of
RR-1801 as the executive runs them on one processor: the threads share memory, there is no
bus). The type-1 updates, their ramps and the run-time arguments of a start are applied by
the automaton task in the controller (:mod:`~orccad_app.sil.generate.adjust`,
:mod:`~orccad_app.sil.generate.binds`); what it cannot apply this process sends as parameter
writes between two jobs (``controller.supervisor_writes`` counts their words: none for the
shipped missions). Robot ports are exchanged every ``exchange_ns``
(the shortest Module-Task period): a sensor read by a job is at most that old, a torque waits
at most that long — a delay the simulated run does not have, so the tracking errors differ a
little (docs/deploy.md).
"""

from __future__ import annotations

import dataclasses
import gc
import os
import tempfile
import time
from collections.abc import Iterator, Sequence
from contextlib import ExitStack, contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from orccad_app.diagnostics import OrccadError
from orccad_app.executive.deadlock import DeadlockError
from orccad_app.executive.kernel import EventClass
from orccad_app.executive.simulation import Simulation, TimingSource
from orccad_app.mission.backend import RunHost
from orccad_app.mission.lifecycle import site_phases
from orccad_app.mission.plan import MissionPlan
from orccad_app.mission.reactor import MissionReactor
from orccad_app.mission.result import RunResult
from orccad_app.mission.run import ReactionError
from orccad_app.sil.build.executable import Prebuilt, build_controller, controller_table
from orccad_app.sil.controller.automaton import ControllerAutomaton
from orccad_app.sil.controller.process import (DEFAULT_HEARTBEAT_S, ControllerFailure,
                                              ControllerProcess, Op)
from orccad_app.sil.controller.remote import ControllerRun, RemoteModule, remote_plan
from orccad_app.sil.generate.adjust import c_adjustments, c_owned_words
from orccad_app.sil.generate.binds import c_binds
from orccad_app.sil.generate.automaton import (MissionProgram, managed_sites, mission_automaton,
                                              reaction_words)
from orccad_app.sil.generate.library import C_DIR
from orccad_app.sil.realtime.job_trace import JobTrace
from orccad_app.sil.realtime.shared import (JOB_RING, REACTION_RING, JobRecords,
                                           ReactionsLost, SharedMemory)

__all__ = ["ModuleTiming", "RealtimeBackend", "realtime"]

_HEARTBEAT_NS = 100_000_000
_EXCHANGE = EventClass.DELIVERY
"""The exchange with the controller is a delivery: first in its instant."""
_INPUT_LEAD_NS = 20_000_000
"""Injections reach the controller this long ahead of their instant [ns] (it queues at most
256: a reaction period of 1 ms takes 20 inputs in that time)."""
_PLANT_FIFO_PRIORITY = 60
"""The plant server's SCHED_FIFO priority, below the controller's threads' (80 minus the
best Module-Task priority)."""


@contextmanager
def _fifo(priority: int) -> Iterator[bool]:
    """This thread under SCHED_FIFO at ``priority`` while in the block, when permitted (else
    unchanged: yields False)."""
    if not hasattr(os, "sched_setscheduler") or os.environ.get("ORCCAD_NO_FIFO"):
        yield False
        return
    try:
        policy, param = os.sched_getscheduler(0), os.sched_getparam(0)
        os.sched_setscheduler(0, os.SCHED_FIFO, os.sched_param(priority))
    except OSError:
        yield False
        return
    try:
        yield True
    finally:
        os.sched_setscheduler(0, policy, param)


@dataclass(frozen=True)
class ModuleTiming:
    """What the real-time run measured for one Module-Task, beside what ``orccad tcs``
    predicted.

    :param name: the TCS name.
    :param released: jobs released.
    :param lateness_s: release lateness ``(median, p99, max)`` [s] (``None`` without job).
    :param overruns: releases skipped because the thread was still behind.
    :param deadline_misses: jobs that ended after their period.
    :param response_max_s: the longest measured response time [s] (``None``: no job ran).
    :param predicted_s: ``orccad tcs``'s bound on the response time [s] (``None``: no bound).
    """

    name: str
    released: int
    lateness_s: tuple[float, float, float] | None
    overruns: int
    deadline_misses: int
    response_max_s: float | None
    predicted_s: float | None


class RealtimeBackend:
    """``orccad sil --realtime``: the Module-Tasks and the automaton run on the real-time
    controller's threads, this process is the plant server (see the module docstring). A
    :class:`~orccad_app.mission.backend.ModuleTaskBackend`.

    Made once the façade has planned the mission: the controller is written, built (cached)
    and started, its shared memory mapped. :meth:`close` ends and reaps it and removes the
    memory.

    :param plan: the run's plan.
    :param source: the mission file (named in the generated sources).
    :param build_dir: where the generated C goes (default a temporary directory).
    :param heartbeat_s: the controller must answer each request within this [s].
    :param prebuilt: a controller built from ``orccad codegen --controller``'s tree, run
        instead of building one.
    """

    pacing: float | None = 1.0
    input_lead_ns = _INPUT_LEAD_NS
    reacts_on_ticks = False
    """No tick here: the automaton task reacts at its own ticks in the controller."""

    def __init__(self, plan: MissionPlan, source: str, build_dir: Path | None = None,
                 heartbeat_s: float = DEFAULT_HEARTBEAT_S,
                 prebuilt: Prebuilt | None = None) -> None:
        self._mission = mission_automaton(plan)
        self._stack = ExitStack()
        started, self._shared = self._stack.enter_context(
            realtime(plan, source, build_dir, heartbeat_s, self._mission, prebuilt))
        self.table, self.controller = started.table, started.controller
        """The controller's generated table (a Module-Task's index: ``table.index(name)``)
        and the controller process."""
        self.automaton: ControllerAutomaton | None = None
        """The mission's automaton in the controller, once the run is made."""
        self.shared_memory_path = self._shared.path
        """The shared memory's file (removed as soon as the controller has mapped it)."""
        self.timings: list[ModuleTiming] | None = None
        """What was measured per Module-Task, once the run has ended."""
        self._plan = started.plan
        self._module_tasks = {task.name: task for task in plan.tcs.module_tasks}
        managed_numbers = managed_sites(plan)
        self._managed_sites = [site for site in self._plan.sites
                               if site.number in managed_numbers]
        self._managed = frozenset(name for site in self._managed_sites for name in site.modules)
        self.exchange_ns = min(task.period_ns for task in plan.tcs.module_tasks)
        """How often the plant and the controller exchange [ns] (the shortest period)."""
        self._ports = [(k, port, port.robot, port.port)
                       for k, port in enumerate(self.table.robot_ports)]
        self._seen_actuators = [0] * len(self.table.robot_ports)
        self._seqs = [0] * len(self.table.entries)
        self._next_ping = 0
        self._jobs_wanted = False  # decided at t = 0, once the observers are known
        self._run: RunHost | None = None
        self._simulation: Any = None
        self._writes: list[Any] = []
        self._jobs: JobTrace | None = None
        self._last_reaction_ns = 0
        self._readers: list[list[tuple[str, str]]] = []
        """Per robot port, the Module-Task input ports it feeds (``on_read`` at each
        exchange: the trace's ``/plant`` topics)."""

    def run_plan(self, plan: MissionPlan) -> MissionPlan:
        """A copy of ``plan``: the full automaton, sites whose starts make proxies (those
        without run-time arguments started by the controller itself)."""
        return self._plan

    def reactor(self, plan: MissionPlan) -> MissionReactor:
        """The controller's C automaton, whose reactions are replayed here."""
        self.automaton = ControllerAutomaton(self.controller, self._mission.program,
                                             self._mission.automaton)
        return self.automaton

    def attach(self, run: RunHost, simulation: Simulation) -> None:
        """The exchange scheduled at t = 0, before the instant's reactions: the epoch and
        the first sensors are there before the automaton activates anything (a trajectory's
        clock then starts with the plant's), and at every exchange the events are read
        before the instant's tick."""
        self._run, self._simulation = run, simulation
        hooks = simulation.hooks
        self._writes = [(m, entry.name,
                         [(slot, port.name, port.type, port.dim,
                           hooks.write_listeners(entry.name, port.name))
                          for slot, port in enumerate(entry.layout.outputs)
                          if port.type != "event"])
                        for m, entry in enumerate(self.table.entries)]
        self._jobs = JobTrace(hooks, self.table)
        table = self.table
        self._readers = [[(table.entries[c.dst_module].name,
                           table.entries[c.dst_module].layout.inputs[c.dst_slot].name)
                          for c in table.connections if c.src_module == -1 and c.src_slot == k]
                         for k in range(len(table.robot_ports))]
        run.kernel.schedule(0, _EXCHANGE, self._exchange)

    # -- the Module-Tasks' lifecycle, sent to the controller (but the managed sites') ------

    def _indices(self, modules: Sequence[str]) -> list[int]:
        return [self.table.index(name) for name in modules if name not in self._managed]

    def activate(self, modules: Sequence[str], at_ns: int) -> None:
        """One request for all ``modules``: their first releases are one instant."""
        indices = self._indices(modules)
        if indices:
            self.controller.request_ints(Op.ACTIVATE, indices, t_s=at_ns / 1e9)

    def kill(self, modules: Sequence[str], at_ns: int) -> None:
        for index in self._indices(modules):
            self.controller.request(Op.KILL, index)

    def reset_ports(self, modules: Sequence[str], at_ns: int) -> None:
        for index in self._indices(modules):
            self.controller.request(Op.RESET, index)

    def take_input(self, name: str, value: Any, at_ns: int) -> bool:
        """An input (an injection handed ``input_lead_ns`` ahead, or raised now by an
        observer's callback), queued in the controller for the automaton task's first
        reaction at or after ``at_ns``, whatever the plant server's lateness."""
        assert self.automaton is not None
        self.controller.request_words(Op.INPUT, self.automaton.input_words(name, value, at_ns))
        return True

    # -- the exchange with the controller ---------------------------------------------------

    def _exchange(self, _: object) -> None:
        run, simulation, shared = self._run, self._simulation, self._shared
        assert run is not None and self._jobs is not None
        kernel = run.kernel
        now = kernel.now
        if now == 0:
            shared.set_epoch(time.monotonic_ns())
            self._jobs_wanted = self._jobs.wanted  # before the first release
            shared.want_jobs(self._jobs_wanted)
        kernel.schedule(now + self.exchange_ns, _EXCHANGE, self._exchange)
        plants = simulation.plants
        on_read = simulation.hooks.on_read
        active = self._active(run) if on_read else frozenset()
        for k, port, robot, name in self._ports:
            plant = plants.get(robot)
            if plant is None:
                continue
            if port.actuator:
                seq, value = shared.read_port(k, port.dim)
                if value is not None and seq != self._seen_actuators[k]:
                    self._seen_actuators[k] = seq
                    plant.actuate(name, value)
            else:
                sample = plant.sample(name)
                shared.write_port(k, sample)
                if on_read:
                    self._read(now, k, sample, active)
        if now == 0:  # the automaton task starts once the first sensors are there: the
            self.controller.request(Op.EPOCH)  # Module-Tasks it activates read them
        self._apply_reactions(run)
        if self._jobs_wanted:
            self._hand_jobs(shared.jobs(), now)
        for m, name, ports in self._writes:  # each job's outputs, to the write listeners
            if shared.seq(m) == self._seqs[m]:   # (the trace; the task error's samples)
                continue
            mirror = shared.mirror(m)
            self._seqs[m] = mirror.seq
            for slot, port, kind, dim, listeners in ports:
                row = mirror.outputs[slot]
                if not listeners or not row[0]:
                    continue
                written: Any = (row[1:1 + dim].copy() if kind == "vector" else
                                bool(row[1]) if kind == "bool" else float(row[1]))
                for hook in listeners:
                    hook(now, name, port, written)
        if now >= self._next_ping:
            self._next_ping = now + _HEARTBEAT_NS
            cycle = self.controller.request_ints(Op.PING)
            if cycle:
                raise self._deadlock(now, cycle)

    def _active(self, run: RunHost) -> frozenset[str]:
        """The Module-Tasks the running Robot-Tasks' phases activate now."""
        phases = run.phases
        return frozenset(module for site in self._plan.sites
                         for module in site.wanted(phases.get(site.number, 0)))

    def _read(self, now: int, k: int, sample: Any, active: frozenset[str]) -> None:
        """The sample of robot port ``k`` the active Module-Tasks it feeds read from now on,
        to the observers' ``on_read`` (as each job's read in lockstep: the trace's
        ``/plant`` topics and the robot's joint states)."""
        assert self._simulation is not None
        for module, port in self._readers[k]:
            if module in active:
                for hook in self._simulation.hooks.on_read:
                    hook(now, module, port, sample)

    def _apply_reactions(self, run: RunHost) -> None:
        """The reactions the automaton task made since the last exchange, applied in order
        (the Robot-Tasks started, killed and retuned over the socket; the report's records)."""
        assert self.automaton is not None
        try:
            reactions = self._shared.reactions()
        except ReactionsLost as lost:
            raise ControllerFailure(f"the plant server fell more than {REACTION_RING} "
                                    f"reactions behind the automaton task ({lost} lost)") from None
        for words in reactions:
            try:
                at_ns, inputs, step = self.automaton.replay(words)
            except OrccadError as error:
                raise ReactionError(error.message, error.location, error.notes) from None
            self._retire_restarted(run, step.outputs)
            self._last_reaction_ns = max(self._last_reaction_ns, at_ns)
            run.apply_reaction(at_ns, inputs, step)
            if run.reactor.finished:
                break

    def _retire_restarted(self, run: RunHost, outputs: tuple[str, ...]) -> None:
        """The sites the automaton task restarted in this reaction have fresh Module-Tasks in
        the controller already: their previous proxies write no parameter any more (a type-1
        update of the previous run, applied in the same reaction, is dropped with it)."""
        starting = [site for site in self._managed_sites if site.start_signal in outputs]
        if not starting:
            return
        before, after = run.phases, site_phases(run.reactor.labels)
        for site in starting:
            if before.get(site.number, 0) > 0 and after.get(site.number, 0) > 0:
                for name in site.modules:
                    compute = self._module_tasks[name].compute
                    if isinstance(compute, RemoteModule):
                        compute.retire()

    def _deadlock(self, now: int, cycle: tuple[int, ...]) -> DeadlockError:
        """The controller's jobs waiting on each other (the PING's answer: per job, its
        Module-Task, the connection and whether it reads), as the executive words it."""
        table = self.table
        waits, ports = [], []
        for at in range(0, len(cycle), 3):
            module, reading = table.entries[int(cycle[at])].name, bool(cycle[at + 2])
            connection = table.connections[int(cycle[at + 1])]
            slot = connection.dst_slot if reading else connection.src_slot
            entry = table.entries[connection.dst_module if reading else connection.src_module]
            port = (entry.layout.inputs if reading else entry.layout.outputs)[slot].name
            other = table.entries[connection.src_module if reading else connection.dst_module]
            ports.append(f"{module}.{port}")
            waits.append(f"{module}.{port} ({'read' if reading else 'write'}, "
                         f"{connection.protocol}) waits for {other.name}")
        return DeadlockError(f"deadlock on the controller's threads at t = {now} ns: "
                             + "; ".join(waits), tuple(ports), now)

    # -- around the run, and after it -------------------------------------------------------

    @contextmanager
    def running(self) -> Iterator[None]:
        """The run with this thread (the plant server) under ``SCHED_FIFO`` where permitted,
        below the controller's threads, and Python's cyclic garbage collector paused, so that
        the plant keeps to the wall clock on a busy machine; both restored after."""
        gc.collect()  # the cyclic collector paused during the run: a pause of the plant
        gc.disable()  # server is a plant falling behind the wall clock
        try:
            with _fifo(_PLANT_FIFO_PRIORITY):
                yield
        finally:
            gc.enable()

    def finish(self, result: RunResult) -> RunResult:
        """The job records up to the run's end handed on (the controller records no more),
        the runtime statistics filled with what was measured (:attr:`timings`), the timing
        source ``measured``."""
        if self._jobs_wanted:
            self._shared.want_jobs(False)
            self._hand_jobs(self._shared.jobs(), result.sim_time_ns, end=True)
        self.timings = self._measured()
        return dataclasses.replace(  # the controller's clock may be ahead of the plant
            result, sim_time_ns=max(result.sim_time_ns, self._last_reaction_ns),  # server's
            stats=dataclasses.replace(result.stats, timing=TimingSource.MEASURED))

    def _hand_jobs(self, batch: JobRecords, now: int, end: bool = False) -> None:
        """The controller's job records to the observers (:class:`JobTrace`); a warning to
        them when the ring was overrun (the records lost are counted, the run goes on)."""
        assert self._run is not None and self._jobs is not None
        if batch.lost:
            self._run.warn("sil", f"{batch.lost} job records lost from the trace: the plant "
                                  f"server fell more than {JOB_RING} records behind the "
                                  f"controller")
        self._jobs.hand(batch, now, end)

    @property
    def job_records_lost(self) -> int:
        """Job records the controller overwrote in the shared memory's ring before the
        plant server could hand them to the trace (0 unless it fell far behind)."""
        return 0 if self._jobs is None else self._jobs.lost

    def _measured(self) -> list[ModuleTiming]:
        """What was measured per Module-Task, the runtime statistics filled with it."""
        predicted = _predicted_response_s(self._plan)
        timings = []
        for m, entry in enumerate(self.table.entries):
            mirror = self._shared.mirror(m)
            late = self._shared.latenesses_ns(m) / 1e9
            lateness = None if not late.size else (float(np.median(late)),
                                                   float(np.percentile(late, 99)),
                                                   float(late.max()))
            response = mirror.response_max_ns / 1e9 if mirror.released else None
            timings.append(ModuleTiming(entry.name, mirror.released, lateness, mirror.overruns,
                                        mirror.misses, response, predicted.get(entry.name)))
            stats = self._simulation.tasks[entry.name].stats
            stats.released = stats.completed = mirror.released
            stats.overruns, stats.late = mirror.overruns, mirror.misses
            stats.response_max_ns = int(mirror.response_max_ns)
        return timings

    def close(self) -> None:
        """End and reap the controller and remove its shared memory."""
        self._stack.close()


def _predicted_response_s(plan: MissionPlan) -> dict[str, float]:
    """``orccad tcs``'s response-time bound of every Module-Task, per Robot-Task [s]."""
    from orccad_app.mission.tcs_bridge import task_tcs
    from orccad_app.tcs.schedulability import analyse_timing

    bounds: dict[str, float] = {}
    for site in plan.sites:
        analysis = analyse_timing(task_tcs(site.instance))
        for local, name in zip(site.instance.modules, site.modules):
            timing = analysis.tasks.get(local)
            if timing is not None and timing.response_ns is not None:
                bounds[name] = timing.response_ns / 1e9
    return bounds


@contextmanager
def realtime(plan: MissionPlan, source: str, build_dir: Path | None = None,
             heartbeat_s: float = DEFAULT_HEARTBEAT_S, automaton: MissionProgram | None = None,
             prebuilt: Prebuilt | None = None
             ) -> Iterator[tuple[ControllerRun, SharedMemory]]:
    """While in the block, the real-time controller of ``plan`` runs (its threads idle until
    activated), the mission's ``automaton`` linked in; the block gets it, the plan a run of
    it runs (a copy: :func:`~orccad_app.sil.controller.remote.remote_plan`) and the shared
    memory. Ended, reaped and its shared memory removed when the block ends."""
    automaton = automaton or mission_automaton(plan)
    if prebuilt is not None:
        table, executable = controller_table(plan, automaton.program), prebuilt.executable
    else:
        with tempfile.TemporaryDirectory(prefix="orccad-sil-") as scratch:
            table, executable = build_controller(plan, source, build_dir or Path(scratch),
                                                 automaton.program, "orccad_rt.c",
                                                 (C_DIR / "orccad_io_shm.c",),
                                                 ("-lm", "-pthread"))
    shared = SharedMemory(len(table.robot_ports), len(table.entries),
                          reaction_words(automaton.program))
    try:
        controller = ControllerProcess(executable, len(table.entries), table.digest,
                                       heartbeat_s, ("--io", shared.path),
                                       prebuilt.wrapper if prebuilt is not None else ())
        shared.unlink()  # the controller answered HELLO: it has mapped the file
        try:
            managed = managed_sites(plan)
            owned = c_owned_words(c_adjustments(plan, table, managed), table)
            bound: dict[str, set[int]] = {}
            for bind in c_binds(plan)[0]:
                bound.setdefault(bind.module, set()).add(bind.offset)
            yield ControllerRun(controller, table, remote_plan(
                plan, automaton.automaton, table, controller, managed, owned,
                {name: frozenset(words) for name, words in bound.items()})), shared
        finally:
            controller.close()
    finally:
        shared.close()
