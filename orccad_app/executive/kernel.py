"""The discrete-event kernel: integer-nanosecond time, a deterministic event queue, seeded RNG.

**Ordering.** Events are kept in a binary heap ordered by ``(time_ns, event class, sequence)``:
the instant first, then the :class:`EventClass` (documented below: e.g. a job that finishes at
``t`` writes its outputs before a job released at ``t`` reads them), then insertion order.
Nothing else (no hash order, no float time) enters the ordering, so a run is reproducible bit
for bit.

**Randomness.** One integer seed drives everything. :meth:`Kernel.stream` derives an independent
``numpy.random.Generator`` per *name* (``"mt/ctrl/duration"``, ``"plant/arm/q"``) as
``PCG64(SeedSequence(seed, spawn_key=K(name)))`` where ``K(name)`` is the first 16 bytes of
``sha256(name.encode())`` read as four big-endian 32-bit words. A stream depends only on the seed
and its name, not on how many other streams exist or when they were created, so adding a noisy
sensor does not change the execution times drawn for a Module-Task.

**Cancellation.** :meth:`Kernel.schedule` returns the queue entry; :meth:`Kernel.cancel` marks it
dead (lazy deletion), which is how a preempted job's completion event is withdrawn.

**Last of the instant.** :meth:`Kernel.defer` is :meth:`Kernel.schedule` at the current instant
in class ``DISPATCH`` (the last class) without the heap: such events wait in a FIFO that runs
when no heap event of the instant is left, which is exactly where the heap would have run them
(``DISPATCH`` events of one instant run in insertion order, after every other class). Each takes
a sequence number as a scheduled event does, so the numbers other events and jobs get are
unchanged. A processor's scheduling decision is such an event: fusing it into the loop spares a
heap push and pop and a queue entry per job.
"""

from __future__ import annotations

import hashlib
import heapq
from collections import deque
from enum import IntEnum
from typing import Any, Callable

import numpy as np

from orccad_app.diagnostics import OrccadError

__all__ = ["EventClass", "Kernel", "stream_key"]


class EventClass(IntEnum):
    """Priority class of events that share an instant; lower runs first."""

    DELIVERY = 0
    """A bus message arrives: its value is visible to reads at the same instant."""
    FINISH = 1
    """A job's compute phase ends: it writes its outputs before same-instant releases read."""
    WAKE = 2
    """A blocked job resumes because its partner acted earlier in this instant."""
    CONTROL = 3
    """Activation, kill, parameter change, user callbacks (the automata's reactions): a kill at
    ``t`` prevents the release at ``t``; an activation at ``t`` releases at ``t``."""
    RELEASE = 4
    """A periodic release of a Module-Task job."""
    DISPATCH = 5
    """A processor's scheduling decision, after every state change of the instant (so jobs
    released together compete together: the critical instant)."""


def stream_key(name: str) -> tuple[int, int, int, int]:
    """The spawn key of the random stream called ``name`` (see the module docstring)."""
    digest = hashlib.sha256(name.encode("utf-8")).digest()
    a, b, c, d = (int.from_bytes(digest[i:i + 4], "big") for i in range(0, 16, 4))
    return a, b, c, d


class Kernel:
    """Event queue and clock.

    :param seed: the run's seed (a non-negative integer).
    """

    __slots__ = ("now", "seed", "_queue", "_last", "_seq", "_streams", "events_processed",
                 "stopped")

    def __init__(self, seed: int = 0) -> None:
        if not isinstance(seed, int) or seed < 0:
            raise OrccadError(f"seed must be a non-negative integer, got {seed!r}")
        self.now = 0
        """The current instant [ns]."""
        self.seed = seed
        self._queue: list[list[Any]] = []
        self._last: deque[tuple[Callable[[Any], None], Any]] = deque()
        """Deferred events of the current instant (:meth:`defer`), in order."""
        self._seq = 0
        self._streams: dict[str, np.random.Generator] = {}
        self.events_processed = 0
        """How many events have run (cancelled ones excluded)."""
        self.stopped = False
        """Set by :meth:`stop`: :meth:`run` returns after the current event."""

    def schedule(self, time_ns: int, klass: int, action: Callable[[Any], None],
                 arg: Any = None) -> list[Any]:
        """Run ``action(arg)`` at ``time_ns`` (>= now) in class ``klass``; return the entry."""
        if time_ns < self.now:
            raise OrccadError(f"cannot schedule an event in the past: {time_ns} ns < "
                              f"now {self.now} ns")
        self._seq += 1
        entry = [time_ns, klass, self._seq, action, arg]
        heapq.heappush(self._queue, entry)
        return entry

    def defer(self, action: Callable[[Any], None], arg: Any = None) -> None:
        """Run ``action(arg)`` now in class ``DISPATCH``: after every other event of this
        instant, in the order of the calls (as ``schedule(now, DISPATCH, ...)``, without the
        heap; such an event cannot be cancelled)."""
        self._seq += 1
        self._last.append((action, arg))

    @staticmethod
    def cancel(entry: list[Any] | None) -> None:
        """Withdraw a scheduled event (no effect if it already ran)."""
        if entry is not None:
            entry[3] = None

    def peek_ns(self) -> int | None:
        """The instant of the next live event, or ``None`` when the queue is empty."""
        if self._last:
            return self.now
        queue = self._queue
        while queue and queue[0][3] is None:
            heapq.heappop(queue)
        return queue[0][0] if queue else None

    def stop(self) -> None:
        """Make :meth:`run` return after the current event, the clock left at its instant
        (a mission that ends before ``until``); the next :meth:`run` clears the request."""
        self.stopped = True

    def run(self, until_ns: int) -> None:
        """Process every event strictly before ``until_ns``, then set the clock to it
        (unless :meth:`stop` was called: the clock then stays at the stopping instant)."""
        queue = self._queue
        last = self._last
        pop = heapq.heappop
        count = 0
        self.stopped = False
        try:
            while True:
                if last and (not queue or queue[0][0] != self.now) and self.now < until_ns:
                    action, arg = last.popleft()  # no heap event left at this instant
                elif queue and queue[0][0] < until_ns:
                    entry = pop(queue)
                    action = entry[3]
                    if action is None:
                        continue
                    self.now = entry[0]
                    entry[3] = None
                    arg = entry[4]
                else:
                    break
                count += 1
                action(arg)
                if self.stopped:
                    return
        finally:
            self.events_processed += count
        if until_ns > self.now:
            self.now = until_ns

    def run_instant(self) -> int | None:
        """Process every event of the next pending instant (without moving the clock past
        it); return that instant [ns], or ``None`` when the queue is empty."""
        instant = self.peek_ns()
        if instant is None:
            return None
        queue = self._queue
        last = self._last
        pop = heapq.heappop
        while True:
            if queue and queue[0][0] == instant:
                entry = pop(queue)
                action = entry[3]
                if action is None:
                    continue
                self.now = instant
                entry[3] = None
                arg = entry[4]
            elif last:
                action, arg = last.popleft()
            else:
                break
            self.events_processed += 1
            action(arg)
            if self.stopped:
                break
        return instant

    def stream(self, name: str) -> np.random.Generator:
        """The random generator called ``name`` (created on first use, then reused)."""
        generator = self._streams.get(name)
        if generator is None:
            sequence = np.random.SeedSequence(self.seed, spawn_key=stream_key(name))
            generator = np.random.Generator(np.random.PCG64(sequence))
            self._streams[name] = generator
        return generator
