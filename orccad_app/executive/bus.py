"""The shared bus between processors: per-message transfer time, FIFO contention.

One message is on the bus at a time; others wait in FIFO order. A message occupies the bus for
``transfer_ns`` (data and reply messages) or ``request_ns`` (requests of the pull protocols),
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

    :param messages: messages delivered (``data`` + ``request`` + ``reply``).
    :param by_kind: messages delivered per kind.
    :param busy_ns: time spent transferring [ns] (up to the last ``close``).
    :param queued_ns: total time messages waited for the bus [ns].
    :param max_queued_ns: longest wait [ns].
    :param elapsed_ns: simulated time covered [ns].
    """

    messages: int = 0
    by_kind: dict[str, int] = field(default_factory=dict)
    busy_ns: int = 0
    queued_ns: int = 0
    max_queued_ns: int = 0
    elapsed_ns: int = 0

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
        self.stats = BusStats(by_kind={"data": 0, "request": 0, "reply": 0})
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
        stats.by_kind[kind] += 1
        stats.busy_ns += self._kernel.now - self._transfer_start
        stats.queued_ns += queued
        if queued > stats.max_queued_ns:
            stats.max_queued_ns = queued
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
