"""The executive's run loop: kernel, processors, bus, Module-Tasks, channels and plants.

Build a :class:`Simulation` from a checked :class:`~orccad_app.tcs.graph.TCS`, activate
Module-Tasks, run::

    sim = Simulation(tcs, seed=7, processors=[Processor("cpu0", context_switch_ns=2_000)],
                     bus=Bus(transfer_ns=50_000), plants=[plant], observers=[log])
    sim.activate()                      # every Module-Task, now
    sim.kill(["obs"], at_ns=ms(300))    # what the behaviour automata will drive
    sim.run(until_ns=s(1))
    sim.stats().tasks["ctrl"].response_max_ns

Control methods (``activate``, ``kill``, ``set_param``, ``at``, ``post_signal``) schedule an
event of class ``CONTROL`` at ``at_ns`` (default: now, i.e. in zero time after the current
event), so an observer reacting to a signal can call them from its callback. Processors named
by Module-Tasks but not given are created with the defaults (fixed priority, no overhead); a
connection between different processors crosses ``bus`` (a zero-time :class:`Bus` if none).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from enum import Enum
from typing import Any, Callable, Iterable

from orccad_app.diagnostics import OrccadError
from orccad_app.executive.bus import Bus, BusStats
from orccad_app.executive.channel import (ActuatorChannel, Channel, SensorChannel,
                                          make_channel)
from orccad_app.executive.context import RunContext
from orccad_app.executive.delays import ControllerDelays, PortExchange
from orccad_app.executive.hooks import Hooks
from orccad_app.executive.job import Job, TaskStats
from orccad_app.executive.kernel import EventClass, Kernel
from orccad_app.executive.observer import Observer
from orccad_app.executive.processor import Processor, ProcessorStats
from orccad_app.executive.reaction import Deliver, ReactionServer, SignalRoutes
from orccad_app.executive.sporadic import SporadicStats, sporadic_releases
from orccad_app.executive.task_runtime import ModuleTaskRuntime
from orccad_app.tcs.graph import TCS
from orccad_app.tcs.module_task import PhysicalResource

__all__ = ["Simulation", "RunStats", "TimingSource"]

_CONTROL = EventClass.CONTROL


class _SignalCallback(Observer):
    """Adapts a plain ``callback(t_ns, name, value)`` to the observer interface."""

    def __init__(self, callback: Callable[[int, str, Any], None]) -> None:
        self._callback = callback

    def on_signal(self, t_ns: int, name: str, value: Any) -> None:
        """Forward to the callback."""
        self._callback(t_ns, name, value)


class TimingSource(Enum):
    """Where a run's timing statistics come from."""

    SIMULATED = "simulated"
    """The executive's timing model: every figure of :class:`RunStats`."""
    MEASURED = "measured"
    """A real-time controller's threads (``orccad sil --realtime``): jobs, overruns, deadline
    misses and the longest response time per Module-Task are measured there; the rest
    (response-time means, preemptions, blocking, processor loads) is not."""


@dataclass(frozen=True, slots=True)
class RunStats:
    """Statistics at the end of the last run segment.

    :param time_ns: the simulated time reached [ns].
    :param events: kernel events processed.
    :param tasks: per Module-Task.
    :param processors: per processor.
    :param bus: the bus's, if any connection crosses it.
    :param sporadic: per sporadic Module-Task, its interrupts and releases.
    :param reactions: per automaton reaction server (``automaton@cpu0``), its reactions.
    :param timing: simulated, or measured on a real-time controller's threads.
    """

    time_ns: int
    events: int
    tasks: dict[str, TaskStats]
    processors: dict[str, ProcessorStats]
    bus: BusStats | None
    sporadic: dict[str, SporadicStats] = field(default_factory=dict)
    reactions: dict[str, TaskStats] = field(default_factory=dict)
    timing: TimingSource = TimingSource.SIMULATED


class Simulation:
    """A timed run of a TCS.

    :param tcs: the TCS (checked with ``tcs.check()`` unless ``check=False``).
    :param seed: the run's seed; same TCS, seed and commands give the same run bit for bit.
    :param processors: processor descriptions (others are created with the defaults).
    :param bus: the bus between processors.
    :param plants: plant objects, one per physical resource of the TCS, matched by
        ``plant.resource.name`` (see :class:`~orccad_app.executive.plant.MujocoPlant`).
    :param observers: :class:`~orccad_app.executive.observer.Observer` instances.
    :param delays: what a real controller adds to the ideal timing (the robot's ports
        exchanged on a period, the releases' jitter: :mod:`orccad_app.executive.delays`);
        default none.
    """

    def __init__(self, tcs: TCS, *, seed: int = 0, processors: Iterable[Processor] = (),
                 bus: Bus | None = None, plants: Iterable[Any] = (),
                 observers: Iterable[Observer] = (), check: bool = True,
                 delays: ControllerDelays = ControllerDelays()) -> None:
        if check:
            tcs.check()
        self.tcs = tcs
        self.kernel = Kernel(seed)
        self._observers = list(observers)
        self.hooks = Hooks(self._observers)
        self.context = RunContext(self.kernel, self.hooks)
        self.processors = self._processors(tcs, processors)
        self.bus = bus
        self.plants = self._plants(tcs, plants)
        self.tasks = {task.name: ModuleTaskRuntime(self.context, task,
                                                   self.processors[task.processor])
                      for task in tcs.module_tasks}
        self.channels: dict[str, Channel] = {}
        self._bus_attached = False
        self.reactions: dict[str, ReactionServer] = {}
        """Automata's reaction servers by name (``automaton@cpu0``)."""
        self.signal_routes = SignalRoutes(self.bus_for_transfer)
        """Where observers' signals go (filled by the mission layer)."""
        self._drivers: dict[str, list[ActuatorChannel]] = {}
        """Per plant, the channels writing its actuators (idle when no producer is active)."""
        self.lateness_max_s = 0.0
        """Longest lag behind the wall clock in paced runs [s]."""
        self.lateness_s: list[float] = []
        """Paced runs: per processed instant, how late it ran behind the wall clock [s]
        (0 when on time)."""
        self._wire()
        self.exchange: PortExchange | None = None
        """The robot's ports' exchange when ``delays`` gives it a period."""
        self._model_delays(delays)
        self.sporadic = sporadic_releases(tcs, self.kernel, self.tasks)
        """The interrupt wiring of the sporadic Module-Tasks (``None`` without any)."""
        if self.sporadic is not None:
            self.add_observer(self.sporadic)

    # -- construction ------------------------------------------------------------------------

    def _processors(self, tcs: TCS, given: Iterable[Processor]) -> dict[str, Processor]:
        processors: dict[str, Processor] = {}
        for processor in given:
            if processor.name in processors:
                raise OrccadError(f"duplicate processor name '{processor.name}'")
            processors[processor.name] = processor
        for task in tcs.module_tasks:
            if task.processor not in processors:
                processors[task.processor] = Processor(task.processor)
        for processor in processors.values():
            processor.attach(self.kernel, self.hooks)
        return processors

    def _plants(self, tcs: TCS, plants: Iterable[Any]) -> dict[str, Any]:
        by_name = {}
        resources = {r.name for r in tcs.resources}
        for plant in plants:
            name = plant.resource.name
            if name not in resources:
                raise OrccadError(f"plant '{name}' is not a physical resource of TCS "
                                  f"'{tcs.name}' (add plant.resource to the TCS)")
            by_name[name] = plant
            plant.notify = self._plant_signal
            plant.attach(self.kernel)
        for name in resources - set(by_name):
            raise OrccadError(f"physical resource '{name}' of TCS '{tcs.name}' has no plant")
        return by_name

    def _plant_signal(self, name: str, value: Any) -> None:
        now = self.kernel.now
        for hook in self.hooks.on_signal:
            hook(now, name, value)

    def _wire(self) -> None:
        tcs = self.tcs
        writes: dict[str, list[Channel]] = {}
        for connection in tcs.connections:
            channel = self._channel(connection)
            self.channels[connection.label] = channel
            writes.setdefault(connection.producer, []).append(channel)
        for runtime in self.tasks.values():
            task = runtime.task
            for port in task.inputs:
                feeding = tcs.feeding(f"{task.name}.{port.name}")
                if feeding is not None:
                    runtime.reads.append((port.name, self.channels[feeding.label]))
            for port in task.outputs:
                runtime.writes.append((port.name, port.is_event, None))
                for channel in writes.get(f"{task.name}.{port.name}", ()):
                    runtime.writes.append((port.name, port.is_event, channel))

    def _model_delays(self, delays: ControllerDelays) -> None:
        if delays.exchange_ns:
            self.exchange = PortExchange(self.kernel, delays.exchange_ns)
            for channel in self.channels.values():
                if isinstance(channel, SensorChannel):
                    channel.exchange = self.exchange
                    self.exchange.watch(channel.plant, channel.port)
                elif isinstance(channel, ActuatorChannel):
                    channel.exchange = self.exchange
        if delays.jitter_ns:
            for runtime in self.tasks.values():
                runtime.jitter(delays.jitter_ns)

    def _channel(self, connection: Any) -> Channel:
        producer = self.tcs.module(connection.producer_module)
        consumer = self.tcs.module(connection.consumer_module)
        if isinstance(producer, PhysicalResource):
            return SensorChannel(connection, self.tasks.get(consumer.name),
                                 self.plants[producer.name])
        if isinstance(consumer, PhysicalResource):
            actuator = ActuatorChannel(connection, self.tasks[producer.name],
                                       self.plants[consumer.name])
            self._drivers.setdefault(consumer.name, []).append(actuator)
            return actuator
        out_port = producer.port(connection.producer_port)
        in_port = consumer.port(connection.consumer_port)
        initial = in_port.initial if in_port.initial is not None else out_port.initial_value()
        bus = None
        if producer.processor != consumer.processor:
            bus = self.bus_for_transfer()
        return make_channel(connection, self.tasks[producer.name], self.tasks[consumer.name],
                            initial, bus)

    def bus_for_transfer(self) -> Bus:
        """The bus between processors (a zero-time one made on first use), attached."""
        if self.bus is None:
            self.bus = Bus()
        if not self._bus_attached:
            self.bus.attach(self.kernel, self.hooks)
            self._bus_attached = True
        return self.bus

    def reaction_server(self, processor: str, reaction_ns: int,
                        deliver: Deliver) -> ReactionServer:
        """The reactions of an automaton on ``processor``, each taking ``reaction_ns``
        (:mod:`orccad_app.executive.reaction`); ``deliver(signals)`` is the reaction."""
        if processor not in self.processors:
            self.processors[processor] = Processor(processor)
            self.processors[processor].attach(self.kernel, self.hooks)
        server = ReactionServer(self.context, self.processors[processor], reaction_ns,
                                deliver)
        self.reactions[server.name] = server
        return server

    # -- observers ---------------------------------------------------------------------------

    def add_observer(self, observer: Observer) -> None:
        """Start calling ``observer``'s overridden callbacks."""
        self._observers.append(observer)
        self.hooks.refresh(self._observers)

    def on_signal(self, callback: Callable[[int, str, Any], None]) -> None:
        """Call ``callback(t_ns, name, value)`` for every signal (event port writes and
        posted signals)."""
        self.add_observer(_SignalCallback(callback))

    # -- control -----------------------------------------------------------------------------

    @property
    def now_ns(self) -> int:
        """The current simulated instant [ns]."""
        return self.kernel.now

    def _runtimes(self, modules: Iterable[str] | str | None) -> list[ModuleTaskRuntime]:
        if modules is None:
            return list(self.tasks.values())
        if isinstance(modules, str):
            modules = [modules]
        found = []
        for name in modules:
            if name not in self.tasks:
                known = ", ".join(self.tasks)
                raise OrccadError(f"unknown module-task '{name}' (known: {known})")
            found.append(self.tasks[name])
        return found

    def at(self, time_ns: int | None, callback: Callable[[Simulation], None]) -> None:
        """Call ``callback(sim)`` at ``time_ns`` (default now), in class ``CONTROL``."""
        when = self.kernel.now if time_ns is None else time_ns
        self.kernel.schedule(when, _CONTROL, callback, self)

    def activate(self, modules: Iterable[str] | str | None = None,
                 at_ns: int | None = None) -> None:
        """Start ``modules`` (default all) at ``at_ns`` (default now): first release then."""
        runtimes = self._runtimes(modules)

        def start(sim: Simulation) -> None:
            for runtime in runtimes:
                if not runtime.active:
                    runtime.activate()
                    for hook in sim.hooks.on_activate:
                        hook(sim.kernel.now, runtime.name)
        self.at(at_ns, start)

    def kill(self, modules: Iterable[str] | str | None = None,
             at_ns: int | None = None) -> None:
        """Stop ``modules`` (default all) at ``at_ns`` (default now), aborting their jobs."""
        runtimes = self._runtimes(modules)

        def stop(sim: Simulation) -> None:
            for runtime in runtimes:
                if runtime.active:
                    runtime.kill()
                    for hook in sim.hooks.on_kill:
                        hook(sim.kernel.now, runtime.name)
            sim._idle_undriven()
        self.at(at_ns, stop)

    def _idle_undriven(self) -> None:
        """Plants none of whose actuator writers is active go idle (their idle behaviour)."""
        for name, channels in self._drivers.items():
            if not any(channel.producer is not None and channel.producer.active
                       for channel in channels):
                self.plants[name].go_idle()

    def set_param(self, module: str, name: str, value: Any, at_ns: int | None = None) -> None:
        """Call ``set_param(name, value)`` of ``module``'s compute object at ``at_ns``."""
        runtime = self._runtimes([module])[0]

        def change(sim: Simulation) -> None:
            runtime.set_param(name, value)
            for hook in sim.hooks.on_param:
                hook(sim.kernel.now, module, name, value)
        self.at(at_ns, change)

    def reset_ports(self, modules: Iterable[str], at_ns: int | None = None) -> None:
        """At ``at_ns`` (default now), bring every channel from or to one of ``modules`` back
        to its state before any write (:meth:`Channel.reset
        <orccad_app.executive.channel.Channel.reset>`): fresh ports for a new run."""
        names = {runtime.name for runtime in self._runtimes(modules)}
        channels = [channel for channel in self.channels.values()
                    if channel.connection.producer_module in names
                    or channel.connection.consumer_module in names]

        def reset(sim: Simulation) -> None:
            for channel in channels:
                channel.reset()
        self.at(at_ns, reset)

    def replace_compute(self, module: str, compute: Any) -> None:
        """Give ``module`` a new compute object, now (used by the next job that starts; call
        it before re-activating a Module-Task that must start afresh)."""
        runtime = self._runtimes([module])[0]
        if not callable(getattr(compute, "compute", None)):
            raise OrccadError(f"module-task '{module}': compute object {compute!r} has no "
                              f"compute(t_s, inputs) method")
        runtime.task.compute = compute

    def interrupt(self, module: str, at_ns: int | None = None) -> None:
        """An interrupt of the sporadic ``module`` at ``at_ns`` (default now): released then,
        or deferred to its minimum inter-arrival (:mod:`orccad_app.executive.sporadic`)."""
        releases = self.sporadic.releases if self.sporadic is not None else {}
        if module not in releases:
            self._runtimes([module])
            raise OrccadError(f"module-task '{module}' is periodic: only a sporadic one takes "
                              f"interrupts (sporadic: {', '.join(releases) or 'none'})")
        release = releases[module]
        self.at(at_ns, lambda _: release.interrupt())

    def post_signal(self, name: str, value: Any = True, at_ns: int | None = None) -> None:
        """Surface an external signal (operator input, timer) to observers at ``at_ns``."""
        def emit(sim: Simulation) -> None:
            for hook in sim.hooks.on_signal:
                hook(sim.kernel.now, name, value)
        self.at(at_ns, emit)

    # -- running -----------------------------------------------------------------------------

    def run(self, until_ns: int, realtime: float | None = None) -> RunStats:
        """Process every event before ``until_ns``, bring plants to it, return the stats.

        :param until_ns: the instant to reach [ns] (events at it are left for the next run).
        :param realtime: ``None`` runs as fast as possible; a factor ``f > 0`` paces the run to
            the wall clock, simulated time going ``f`` times as fast as real time; how late
            the run fell behind is kept in :attr:`lateness_max_s` [s].

        A deadlock, a diverging plant or a failing compute object raises an
        :class:`OrccadError`; the statistics then stop at the failing instant. After
        ``sim.kernel.stop()`` (e.g. from an observer: the mission ended) the run returns at
        that instant instead of ``until_ns``.
        """
        if not isinstance(until_ns, int) or until_ns < self.kernel.now:
            raise OrccadError(f"run until {until_ns!r} ns: expected an integer instant >= "
                              f"now ({self.kernel.now} ns)")
        if realtime is not None and not realtime > 0:
            raise OrccadError(f"realtime factor must be > 0, got {realtime!r}")
        try:
            if realtime is None:
                self.kernel.run(until_ns)
            else:
                self._run_paced(until_ns, realtime)
            for plant in self.plants.values():
                plant.advance_to(self.kernel.now)
        finally:
            self._close()
        return self.stats()

    def _run_paced(self, until_ns: int, factor: float) -> None:
        kernel = self.kernel
        kernel.stopped = False
        wall_start = time.perf_counter()
        sim_start = kernel.now
        lateness = self.lateness_s
        while not kernel.stopped:
            following = kernel.peek_ns()
            target = until_ns if following is None or following >= until_ns else following
            delay = wall_start + (target - sim_start) / 1e9 / factor - time.perf_counter()
            if delay > 0:
                time.sleep(delay)
                lateness.append(0.0)
            else:
                lateness.append(-delay)
                if -delay > self.lateness_max_s:
                    self.lateness_max_s = -delay
            if target == until_ns:
                kernel.run(until_ns)
                return
            kernel.run_instant()

    def _close(self) -> None:
        now = self.kernel.now
        for processor in self.processors.values():
            processor.close(now)
        for runtime in self.tasks.values():
            runtime.close(now)
        if self.bus is not None:
            self.bus.close(now)

    def stats(self) -> RunStats:
        """Statistics as of the end of the last run segment (live objects)."""
        return RunStats(self.kernel.now, self.kernel.events_processed,
                        {name: rt.stats for name, rt in self.tasks.items()},
                        {name: p.stats for name, p in self.processors.items()},
                        self.bus.stats if self.bus is not None else None,
                        {} if self.sporadic is None else
                        {name: r.stats for name, r in self.sporadic.releases.items()},
                        {name: server.stats for name, server in self.reactions.items()})

    def check_deadlock(self, job: Job) -> None:
        """Raise :class:`~orccad_app.executive.deadlock.DeadlockError` if ``job`` closes a
        wait cycle (called by the executive whenever a job blocks)."""
        self.context.check_deadlock(job)
