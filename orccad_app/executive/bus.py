"""The shared bus between processors: per-message transfer time, FIFO contention.

One message is on the bus at a time; others wait in FIFO order. A message occupies the bus for
``transfer_ns`` (data, reply and event messages) or ``request_ns`` (requests of the pull
protocols),
then is delivered: its callback runs in an event of class ``DELIVERY``, so a value delivered at
``t`` is visible to reads at ``t``.
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Callable

from orccad_app.diagnostics import OrccadError
from orccad_app.executive.kernel import EventClass, Kernel

if TYPE_CHECKING:
    from orccad_app.executive.hooks import Hooks

__all__ = ["Bus", "BusStats"]

_DELIVERY = EventClass.DELIVERY


@dataclass(slots=True)
class BusStats:
    """Counters of the bus.

    :param messages: messages delivered (``data`` + ``request`` + ``reply`` + ``event``: a
        signal to an automaton, :mod:`orccad_app.executive.reaction`).
    :param by_kind: messages delivered per kind (``event`` from the first one).
    :param busy_ns: time spent transferring [ns] (up to the last ``close``).
    :param queued_ns: total time messages waited for the bus [ns].
    :param max_queued_ns: longest wait [ns].
    :param elapsed_ns: simulated time covered [ns].
    :param queued_by_kind: total wait per message kind [ns].
    :param max_queued_by_kind: longest wait per message kind [ns].
    """

    messages: int = 0
    by_kind: dict[str, int] = field(default_factory=dict)
    busy_ns: int = 0
    queued_ns: int = 0
    max_queued_ns: int = 0
    elapsed_ns: int = 0
    queued_by_kind: dict[str, int] = field(default_factory=dict)
    max_queued_by_kind: dict[str, int] = field(default_factory=dict)

    def by_class(self) -> dict[str, dict[str, float]]:
        """Per message class — ``port_data`` (data, request and reply messages of the
        connections) and ``event`` (signals to an automaton) — ``messages``, ``queued_mean_ns``
        and ``queued_max_ns`` (the wait for the bus)."""
        classes = {"port_data": ("data", "request", "reply"), "event": ("event",)}
        found = {}
        for name, kinds in classes.items():
            count = sum(self.by_kind.get(k, 0) for k in kinds)
            queued = sum(self.queued_by_kind.get(k, 0) for k in kinds)
            found[name] = {"messages": count,
                           "queued_mean_ns": queued / count if count else 0.0,
                           "queued_max_ns": max(self.max_queued_by_kind.get(k, 0)
                                                for k in kinds)}
        return found

    @property
    def busy_ratio(self) -> float:
        """Fraction of the elapsed time the bus was transferring."""
        return self.busy_ns / self.elapsed_ns if self.elapsed_ns else 0.0

    @property
    def mean_queued_ns(self) -> float:
        """Mean wait for the bus per delivered message [ns]."""
        return self.queued_ns / self.messages if self.messages else 0.0


class Bus:
    """A FIFO bus.

    :param name: identifier.
    :param transfer_ns: time a data or reply message occupies the bus [ns].
    :param request_ns: time a request message occupies the bus [ns]; defaults to
        ``transfer_ns``.
    """

    def __init__(self, name: str = "bus", transfer_ns: int = 0,
                 request_ns: int | None = None) -> None:
        for label, value in (("transfer_ns", transfer_ns), ("request_ns", request_ns)):
            if value is not None and (not isinstance(value, int) or value < 0):
                raise OrccadError(f"bus '{name}': {label} must be an integer >= 0, "
                                  f"got {value!r}")
        self.name = name
        self.transfer_ns = transfer_ns
        self.request_ns = transfer_ns if request_ns is None else request_ns
        kinds = ("data", "request", "reply")  # and "event", counted from the first one
        self.stats = BusStats(by_kind=dict.fromkeys(kinds, 0),
                              queued_by_kind=dict.fromkeys(kinds, 0),
                              max_queued_by_kind=dict.fromkeys(kinds, 0))
        self._queue: deque[list[Any]] = deque()
        self._busy = False
        self._transfer_start = 0
        self._kernel: Kernel  # set by attach(), before the run
        self._hooks: Hooks

    def attach(self, kernel: Kernel, hooks: Hooks) -> None:
        """Bind to a simulation's kernel and observer hooks (done by the Simulation)."""
        self._kernel = kernel
        self._hooks = hooks

    @property
    def queue_length(self) -> int:
        """Messages waiting (not counting the one on the bus)."""
        return len(self._queue)

    def send(self, kind: str, label: str, payload: Any,
             then: Callable[[Any], None]) -> None:
        """Queue a ``kind`` message of connection ``label``; ``then(payload)`` on delivery."""
        message = [self._kernel.now, kind, label, payload, then, 0]
        if self._busy:
            self._queue.append(message)
        else:
            self._start(message)

    def _start(self, message: list[Any]) -> None:
        now = self._kernel.now
        self._busy = True
        message[5] = now - message[0]
        duration = self.request_ns if message[1] == "request" else self.transfer_ns
        self._transfer_start = now
        self._kernel.schedule(now + duration, _DELIVERY, self._deliver, message)

    def _deliver(self, message: list[Any]) -> None:
        _, kind, label, payload, then, queued = message
        stats = self.stats
        stats.messages += 1
        stats.by_kind[kind] = stats.by_kind.get(kind, 0) + 1
        stats.busy_ns += self._kernel.now - self._transfer_start
        stats.queued_ns += queued
        if queued > stats.max_queued_ns:
            stats.max_queued_ns = queued
        stats.queued_by_kind[kind] = stats.queued_by_kind.get(kind, 0) + queued
        if queued > stats.max_queued_by_kind.get(kind, 0):
            stats.max_queued_by_kind[kind] = queued
        self._busy = False
        if self._queue:
            self._start(self._queue.popleft())
        for hook in self._hooks.on_message:
            hook(self._kernel.now, self.name, kind, label, queued)
        then(payload)

    def close(self, now_ns: int) -> None:
        """Bring the statistics up to ``now_ns`` (end of a run segment): the part of an
        unfinished transfer already done counts as busy."""
        if self._busy:
            self.stats.busy_ns += now_ns - self._transfer_start
            self._transfer_start = now_ns
        self.stats.elapsed_ns = now_ns
