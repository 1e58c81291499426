"""Signals to a behaviour automaton on its own processor: the bus, then a timed reaction.

RR-1801 §3.2.1: "some messages like exception signals must be sent using safe protocols".
An observer's event signal goes to the automaton of its Robot-Task, which runs on a declared
processor (``automaton on cpu0 reaction 0.05 ms;``):

- **Transport** (:meth:`SignalRoutes.send`). On the automaton's processor the signal is there
  at once. From another processor it crosses the bus as a message of class ``event``, under
  the safe protocol: every signal is its own message, queued in FIFO order behind the port
  data already waiting — never overwritten by a later one (unlike ``asyn/asyn`` data), never
  dropped (no port reset discards it), delivered exactly once. The trace shows its emission
  (``signal``) and its delivery (``message``, kind ``event``, with the time it queued).
- **Reaction** (:class:`ReactionServer`). Delivered signals are handed to the automaton by a
  job of priority 0 (above every Module-Task; under EDF its deadline is its release plus the
  reaction time) that occupies the automaton's processor for the declared reaction time, so
  the reaction happens ``transfer + queueing + reaction`` after the observer wrote, and the
  Module-Tasks of that processor are delayed by it. Signals delivered while a reaction runs
  are handled by the next one; those delivered before it starts join it (one reaction per
  instant, as a synchronous automaton reacts to all the signals present). With a reaction
  time of 0 the signals reach the automaton in the instant they arrive.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from orccad_app.diagnostics import OrccadError
from orccad_app.executive.bus import Bus
from orccad_app.executive.context import RunContext
from orccad_app.executive.job import DONE, Job, TaskStats
from orccad_app.executive.processor import Processor

__all__ = ["ReactionServer", "SignalRoutes", "EVENT", "Deliver"]

EVENT = "event"
"""The bus message kind of a signal to an automaton."""

Deliver = Callable[[list[tuple[str, Any]]], None]
"""``deliver(signals)``: hand ``[(name, value), ...]`` to the automaton (its reaction)."""


class ReactionServer:
    """The reactions of one behaviour automaton, as jobs on its processor.

    :param context: the run's kernel and hooks.
    :param processor: the automaton's processor.
    :param reaction_ns: the execution time of one reaction [ns].
    :param deliver: what a finished reaction does with its signals.
    """

    priority = 0
    active = True

    def __init__(self, context: RunContext, processor: Processor, reaction_ns: int,
                 deliver: Deliver) -> None:
        if not isinstance(reaction_ns, int) or reaction_ns < 0:
            raise OrccadError(f"automaton on {processor.name}: reaction time must be an "
                              f"integer >= 0 ns, got {reaction_ns!r}")
        self.name = f"automaton@{processor.name}"
        self.processor = processor
        self.reaction_ns = reaction_ns
        self.stats = TaskStats()
        self.job: Job | None = None
        self._context = context
        self._deliver = deliver
        self._waiting: list[tuple[str, Any]] = []
        self._count = 0

    def submit(self, name: str, value: Any) -> None:
        """A signal reached the automaton's processor: react (after the reaction time)."""
        if self.reaction_ns == 0:
            self._deliver([(name, value)])
            return
        self._waiting.append((name, value))
        if self.job is None:
            self._start()

    def _start(self) -> None:
        kernel = self._context.kernel
        now = kernel.now
        job = Job(self, self._count, kernel._seq, now, now + self.reaction_ns,
                  self.reaction_ns)
        self._count += 1
        self.stats.released += 1
        self.job = job
        self.processor.make_ready(job)

    def compute(self, job: Job) -> None:
        """The reaction starts: it takes the signals delivered so far."""
        job.outputs = {"signals": self._waiting}
        self._waiting = []

    def compute_done(self, job: Job) -> None:
        """The reaction's execution time is consumed: the automaton reacts now."""
        now = self._context.kernel.now
        job.phase = DONE
        self.job = None
        stats = self.stats
        response = now - job.release_ns
        stats.completed += 1
        stats.response_sum_ns += response
        stats.response_max_ns = max(stats.response_max_ns, response)
        self._deliver(job.outputs["signals"])
        if self._waiting:
            self._start()

    def wake(self, job: Job, value: Any = None) -> None:
        """Never blocked: reactions read and write no port."""

    def check_deadlock(self, job: Job) -> None:
        """Never blocked: nothing to check."""


@dataclass(frozen=True)
class SignalRoute:
    """Where one signal goes: from its observer's processor to its automaton's server."""

    source_processor: str
    server: ReactionServer


class SignalRoutes:
    """The signals of a run's observers, routed to their automata's processors.

    :param bus_for: returns the run's bus (made on first use) for a transfer.
    """

    def __init__(self, bus_for: Callable[[], Bus]) -> None:
        self._bus_for = bus_for
        self._routes: dict[str, SignalRoute] = {}

    def add(self, signal: str, source_processor: str, server: ReactionServer) -> None:
        """Route ``signal`` (``module.port``), written on ``source_processor``, to ``server``."""
        self._routes[signal] = SignalRoute(source_processor, server)

    def send(self, signal: str, value: Any) -> bool:
        """Carry ``signal`` to its automaton; ``False`` when it has no route."""
        route = self._routes.get(signal)
        if route is None:
            return False
        server = route.server
        if route.source_processor == server.processor.name:
            server.submit(signal, value)
        else:
            self._bus_for().send(EVENT, f"{signal} -> {server.name}", (signal, value),
                                 lambda payload: server.submit(*payload))
        return True
