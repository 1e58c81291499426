"""Watching and steering a live mission run, without Textual.

:class:`LiveObserver` is an executive observer (with the mission hooks) that runs on the
executive's thread. At each reaction of the automaton it

- **paces** the run against the wall clock (:class:`Pace`: paused, × factor, or as fast as
  possible) by sleeping;
- schedules the inputs, holds and plant faults the user asked for since the last reaction
  (:meth:`LiveObserver.raise_input`, :meth:`~LiveObserver.hold`,
  :meth:`~LiveObserver.inject_fault`) as ``orccad run --inject`` schedules them
  (:mod:`orccad_app.tui.user_inputs`): the run is the one ``--inject`` at the reported
  instants gives;
- hands a :class:`LiveUpdate` to ``post`` at most every ``flush_s`` wall seconds: the
  automaton's state, the phase of every running Robot-Task, new log entries, new plot samples
  (the task error ``e`` of the control laws, the robots' sensors as their modules read them),
  per-processor load and deadline misses.

It holds no mission logic: everything it reports is what the executive did.
"""

from __future__ import annotations

import math
import threading
import time
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Any, Callable, Iterator

import numpy as np

from orccad_app.control.ports import TASK_ERROR
from orccad_app.diagnostics import arguments_text
from orccad_app.executive.observer import Observer
from orccad_app.robottask.labels import Phase
from orccad_app.trace.report import InjectionRecord
from orccad_app.trace.writers import sensor_ports
from orccad_app.tui.pace import Pace, new_event
from orccad_app.tui.run_process import Request, RunEnded
from orccad_app.tui.user_inputs import UserInputs

__all__ = ["LogEntry", "LiveUpdate", "LiveObserver", "sensor_ports", "StateView",
           "SeenStates"]

SETPOINT_PORTS = ("qd",)
"""Output ports sampled as set-points: ``qd[i]`` is plotted over ``ROBOT.q[i]``."""

BUSY_FRAME_S = 0.25
"""While the run goes as fast as it can, a frame every this much CPU time [s] of the run's own
thread (else every ``flush_s`` of wall time), and only once the screen has taken the previous
one (:meth:`LiveObserver.frame_taken`): the screen's drawing shares the interpreter with the
run, so frames follow the run's progress, not the wall clock (on a loaded machine a wall-clock
rate would draw more frames per simulated second, each taking time from the run)."""

"""Name of each phase of a Robot-Task's RTA (docs/language.md: pre-conditions, then control)."""


@dataclass(frozen=True)
class LogEntry:
    """One line of the run's log. ``kind``: ``task``, ``input``, ``fault``, ``output``,
    ``exception``, ``miss``, ``param`` or ``status``. ``task_start`` marks a task start
    (for the plots' markers)."""

    time_ns: int
    kind: str
    text: str
    task_start: bool = False

    def format(self) -> str:
        return f"{self.time_ns / 1e9:9.3f} s  {self.kind:<9} {self.text}"


@dataclass
class LiveUpdate:
    """What changed since the previous update (samples and log entries are new ones only)."""

    time_ns: int
    state: int | None
    status: str
    speed: str
    tasks: list[tuple[str, int, int]] = field(default_factory=list)
    log: list[LogEntry] = field(default_factory=list)
    samples: dict[str, list[tuple[float, float]]] = field(default_factory=dict)
    """Series name -> new ``(t [s], value)`` samples."""
    loads: dict[str, float] = field(default_factory=dict)
    misses: dict[str, int] = field(default_factory=dict)
    wall_s: float = 0.0
    """``time.perf_counter()`` when the update was made (actual speed = Δt / Δwall)."""
    paused_s: float = 0.0
    """Wall time spent paused so far [s]."""
    held: tuple[str, ...] = ()
    """Inputs held (raised at every instant until released)."""
    states: dict[int, StateView] = field(default_factory=dict)
    """What the screen reads of the automaton about ``state`` when it is a state not shown
    before: the automaton is built as the run reaches its states (a lazy automaton), in the
    run's process (:class:`SeenStates`)."""


@dataclass(frozen=True)
class StateView:
    """A state of the mission's automaton as the screen reads it: its labels (running
    Robot-Tasks, sub-missions) and the statements it waits at."""

    labels: frozenset
    waiting: tuple


class SeenStates:
    """The states of the automaton that a run in another process has shown, with the
    ``labels`` and ``waiting`` of an automaton (indexed by state; empty for states not
    seen): what :mod:`orccad_app.tui.status` reads."""

    def __init__(self) -> None:
        self.labels: list[frozenset] = []
        self.waiting: list[tuple] = []

    def learn(self, states: dict[int, StateView]) -> None:
        for state, view in states.items():
            while len(self.labels) <= state:
                self.labels.append(frozenset())
                self.waiting.append(())
            self.labels[state], self.waiting[state] = view.labels, view.waiting


def _components(value: Any, limit: int = 6) -> list[float] | None:
    try:
        values = np.asarray(value, dtype=float).ravel()
    except (TypeError, ValueError):
        return None
    return [float(v) for v in values[:limit]] if values.size else None


class LiveObserver(Observer):
    """See the module docstring.

    :param run: the :class:`~orccad_app.mission.run.MissionRun` observed.
    :param post: called with each :class:`LiveUpdate` (on the executive's thread).
    :param pace: the run's speed.
    :param sample_ns: plot sampling period [ns] (simulated time).
    :param flush_s: how often updates are posted [s] (wall time).
    :param scripted: ``(time [ns], input)`` of the injections a script raises (logged as
        raised ``by`` ``scripted_by`` when they reach the automaton).
    :param wait_for_screen: post a frame only once the previous one was taken
        (:meth:`frame_taken`; a pause's frame always goes): a screen that falls behind gets
        fewer, fuller frames and never shows an old state; and a paced run waits at its
        first frame until the screen shows it (its pacing starts then).
    """

    def __init__(self, run: Any, post: Callable[[LiveUpdate], None], pace: Pace, *,
                 sample_ns: int = 10_000_000, flush_s: float = 0.1,
                 scripted: set[tuple[int, str]] | frozenset[tuple[int, str]] = frozenset(),
                 scripted_by: str = "", wait_for_screen: bool = False) -> None:
        self.run, self.post, self.pace = run, post, pace
        self.wait_for_screen = wait_for_screen
        self._scripted, self._scripted_by = scripted, scripted_by
        self.sample_ns, self.flush_s = sample_ns, flush_s
        self._sensors = sensor_ports(run.plan)
        self._site_task = {site.number: site.task for site in run.plan.sites}
        self._outputs = set(run.plan.roles.own(s.name for s in run.plan.automaton.outputs))
        self.inputs = UserInputs(run, self._log_entry)
        """The user's inputs, holds and faults (:mod:`orccad_app.tui.user_inputs`)."""
        self._abort: str | None = None
        self._present: set[str] = set()
        self._next_sample: dict[str, int] = {}
        self._samples: dict[str, list[tuple[float, float]]] = {}
        self._log: list[LogEntry] = []
        self._window: tuple[int, dict[str, int]] = (0, {})  # (instant, busy [ns] per cpu)
        self._misses: dict[str, int] = {}
        self._flushed_at = 0.0  # wall time [s] of the last frame
        self._flushed_cpu = 0.0  # the run thread's CPU time [s] at the last frame
        self._posted = 0  # frames posted ...
        self._taken = 0  # ... and taken by the screen (frame_taken)
        self._forward: Callable[[Request], None] | None = None  # to the run's process
        self._remote = False  # the run is (or was) in another process
        self._held: dict[str, Any] = {}  # ... and these inputs are held there
        self._described: set[int] = set()  # states whose StateView was posted
        self._screen_up = threading.Event()  # the screen took a frame (or the run ends)
        self._adopted: list[InjectionRecord] | None = None  # ... and raised there
        self.reactions = 0
        """Reactions seen so far."""
        self.aborted_at: int | None = None
        """The reaction (its count) at which the user's abort ended the run."""

    # -- from the UI's thread --------------------------------------------------------------

    def raise_input(self, name: str, value: Any = None) -> None:
        """Raise input ``name`` once, as ``--inject`` would at the due instant."""
        self._request(Request("pulse", name, value))

    def hold(self, name: str, value: Any = None) -> None:
        """Raise input ``name`` at every tick from the due instant until :meth:`release`."""
        self._request(Request("hold", name, value))

    def release(self, name: str) -> None:
        """Stop holding input ``name``."""
        self._request(Request("release", name))

    @property
    def held(self) -> tuple[str, ...]:
        return tuple(self._held) if self._remote else self.inputs.held

    def inject_fault(self, name: str, value: Any) -> None:
        """Apply the plant fault ``ROBOT.FAULT`` at the due instant, as
        ``orccad run --inject ROBOT.FAULT=VALUE@T`` does; a value out of the fault's declared
        range raises :class:`~orccad_app.diagnostics.OrccadError` now, as ``--inject``
        refuses it."""
        self.inputs.check_fault(name, value)
        self._request(Request("fault", name, value))

    @property
    def injected(self) -> list[InjectionRecord]:
        """What the user raised, once it reached the run (for the report): one record per
        pulse and fault, one per hold."""
        return list(self._adopted) if self._adopted is not None else self.inputs.records()

    def abort(self, reason: str = "stopped by the user") -> None:
        """End the run at the next reaction (status ``aborted``)."""
        self._request(Request("abort", reason))

    def frame_taken(self) -> None:
        """The screen has handled a posted :class:`LiveUpdate` (the next frame may come)."""
        self._request(Request("taken"))

    # -- a run in another process (orccad_app.tui.run_process) ------------------------------

    def forward(self, send: Callable[[Request], None] | None) -> None:
        """From now on send the user's requests (and the speed's changes) with ``send`` to
        the run's process instead of applying them here (``None``: stop sending)."""
        self._forward = send
        if send is not None:
            self._remote = True
            self.pace.on_change = lambda factor: send(Request("pace", value=factor))
        else:
            self.pace.on_change = None

    @contextmanager
    def forking(self) -> Iterator[None]:
        """Around ``os.fork()`` of the run's process: the UI's thread may be changing the
        pace at that instant, and a lock held then would stay held in the child forever."""
        with self.pace.forking():
            yield

    def local(self) -> None:
        """In the run's process, just forked under :meth:`forking`: requests are applied
        here (:meth:`apply`); the events are made anew, as they were (another thread of the
        parent may have been inside one when it forked)."""
        self._forward, self._remote, self.pace.on_change = None, False, None
        self._screen_up = new_event(self._screen_up.is_set())
        self.pace.after_fork()

    def adopt(self, ended: RunEnded) -> None:
        """Take what the run's process reported at its end (the user's injections, the
        abort's reaction, the reactions)."""
        self._adopted = list(ended.injected)
        self.aborted_at, self.reactions = ended.aborted_at, ended.reactions

    def _request(self, request: Request) -> None:
        send = self._forward
        if send is None:
            self.apply(request)
            return
        if request.what == "hold":
            self._held.setdefault(request.name, request.value)
        elif request.what == "release":
            self._held.pop(request.name, None)
        elif request.what == "abort":
            self.pace.stop()
        send(request)

    def apply(self, request: Request) -> None:
        """Carry out a user's request here (the UI's thread, or the thread that receives
        them in the run's process)."""
        what, name, value = request.what, request.name, request.value
        if what == "pulse":
            self.inputs.pulse(name, value)
        elif what == "hold":
            self.inputs.hold(name, value)
        elif what == "release":
            self.inputs.release(name)
        elif what == "fault":
            self.inputs.fault(name, value)
        elif what == "abort":
            self._abort = name
            self.pace.stop()
            self._screen_up.set()
        elif what == "pace":
            self.pace.set(value)
        elif what == "taken":
            self._taken += 1
            self._screen_up.set()

    def _log_entry(self, t_ns: int, kind: str, text: str) -> None:
        self._log.append(LogEntry(t_ns, kind, text))

    # -- on the executive's thread -----------------------------------------------------------

    def on_reaction(self, t_ns: int, inputs: tuple[str, ...], outputs: tuple[str, ...],
                    status: str) -> None:
        self.reactions += 1
        if self._abort is not None:
            if self.aborted_at is None:
                self.aborted_at = self.reactions
            self.run.abort(self._abort)
            return
        if inputs and self._scripted:
            for name in inputs:
                if (t_ns, name) in self._scripted:
                    self._log.append(LogEntry(t_ns, "input", f"{name} raised by the "
                                                             f"{self._scripted_by}"))
        if outputs or self._present:
            present = {name for name in outputs if name in self._outputs}
            for name in sorted(present - self._present):  # a sustained output: logged once
                self._log.append(LogEntry(t_ns, "output", name))
            self._present = present
        self.inputs.on_reaction(t_ns)
        pace = self.pace
        ready = self._taken >= self._posted or not self.wait_for_screen
        if pace.factor is None:  # as fast as possible: nothing to wait for
            if ready and time.thread_time() - self._flushed_cpu >= BUSY_FRAME_S:
                self.flush(t_ns)
            return
        if pace.factor == 0 or (ready and time.perf_counter() - self._flushed_at >= self.flush_s):
            self.flush(t_ns)  # before a pause, so that the screen shows where it stopped
            if self.wait_for_screen and self._posted == 1:
                self._screen_up.wait()  # a paced run starts when the screen shows it
        pace.wait(t_ns)

    def flush(self, t_ns: int) -> None:
        """Post what changed since the last update (on the executive's thread)."""
        self._flushed_at, self._flushed_cpu = time.perf_counter(), time.thread_time()
        self._posted += 1
        reactor = self.run.reactor
        tasks = [(self._site_task[site], site, phase)
                 for site, phase in sorted(self.run.phases.items()) if phase is not Phase.IDLE]
        loads = self._loads(t_ns)
        self._count_misses(t_ns)
        update = LiveUpdate(t_ns, reactor.state, reactor.status, self.pace.label, tasks,
                            self._log, self._samples, loads, dict(self._misses),
                            time.perf_counter(), self.pace.paused_s, self.held,
                            self._describe(reactor.state))
        self._log, self._samples = [], {}
        self.post(update)

    def _describe(self, state: int | None) -> dict[int, StateView]:
        """``state``'s :class:`StateView` if not posted before."""
        automaton = self.run.plan.automaton
        if state is None or state in self._described or not 0 <= state < len(automaton.labels):
            return {}
        self._described.add(state)
        waiting = automaton.waiting[state] if state < len(automaton.waiting) else ()
        return {state: StateView(automaton.labels[state], tuple(waiting))}

    def _loads(self, t_ns: int) -> dict[str, float]:
        """Each processor's busy share since the last update, from its statistics."""
        start, busy_then = self._window
        busy = self.run.processor_busy_ns()
        span = t_ns - start
        loads = {p: min(1.0, (b - busy_then.get(p, 0)) / span) if span > 0 else 0.0
                 for p, b in busy.items()}
        self._window = (t_ns, busy)
        return loads

    def _count_misses(self, t_ns: int) -> None:
        """Deadline misses since the last update, from the Module-Tasks' statistics: one log
        line per Module-Task that missed (how many, and how)."""
        for name, total in self.run.missed_jobs().items():
            new = total - self._misses.get(name, 0)
            if new > 0:
                self._misses[name] = total
                self._log.append(LogEntry(t_ns, "miss", f"{name}: {new} deadline "
                                                        f"miss{'es' if new > 1 else ''} "
                                                        f"(finished late or release skipped)"))

    def _sample(self, t_ns: int, name: str, values: list[float] | None) -> None:
        if values is None or t_ns < self._next_sample.get(name, 0):
            return
        self._next_sample[name] = t_ns + self.sample_ns
        t_s = t_ns / 1e9
        if len(values) == 1:
            self._samples.setdefault(name, []).append((t_s, values[0]))
            return
        for index, value in enumerate(values):
            self._samples.setdefault(f"{name}[{index}]", []).append((t_s, value))

    def on_read(self, t_ns: int, module: str, port: str, value: Any) -> None:
        sensor = self._sensors.get((module, port))
        if sensor is not None and t_ns >= self._next_sample.get(sensor, 0):
            self._sample(t_ns, sensor, _components(value))

    def wants_write(self, module: str, port: str) -> bool:
        """Only the set-points and the task errors are plotted."""
        return port in SETPOINT_PORTS or port == TASK_ERROR

    def on_write(self, t_ns: int, module: str, port: str, value: Any) -> None:
        if port in SETPOINT_PORTS:  # the reference: the set-point of the measured joints
            if t_ns >= self._next_sample.get(port, 0):
                self._sample(t_ns, port, _components(value))
            return
        if port == TASK_ERROR and t_ns >= self._next_sample.get("tracking error", 0):
            values = _components(value, limit=1 << 16)
            if values is not None:
                self._sample(t_ns, "tracking error", [math.sqrt(sum(v * v for v in values))])

    def on_param(self, t_ns: int, module: str, name: str, value: Any) -> None:
        self._log.append(LogEntry(t_ns, "param", f"{module}.{name} := {value}"))

    def on_task_start(self, t_ns: int, task: str, site: int, args: dict) -> None:
        shown = f": {arguments_text(args)}" if args else ""  # its actual arguments
        self._log.append(LogEntry(t_ns, "task", f"{task} (site {site}) starts{shown}",
                                  task_start=True))

    def on_task_end(self, t_ns: int, task: str, site: int, outcome: str) -> None:
        self._log.append(LogEntry(t_ns, "task", f"{task} (site {site}) ends: {outcome}"))

    def on_exception(self, record: Any) -> None:
        origin = f" from {record.task}" if record.task else ""
        change = f": {record.update.text()}" if getattr(record, "update", None) else ""
        self._log.append(LogEntry(record.time_ns, "exception",
                                  f"{record.name} (type {record.type.number}){origin}{change}"))
