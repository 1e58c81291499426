"""The real-time controller's job records as the executive's job callbacks, for the trace.

In real time no job runs in this process: the controller's threads record each job's measured
life cycle and each release they skip (``orc_io_job``, a ring in the shared memory,
:meth:`~orccad_app.sil.realtime.shared.SharedMemory.jobs`) while a trace observes the run.
:class:`JobTrace` hands them to the run's observers as ``orccad run``'s executive does —
``on_release``, ``on_start``, ``on_compute_end``, ``on_finish`` (``response_ns`` from the
release, ``missed`` after the period), ``on_overrun`` (the unfinished job) — with the
Module-Task's TCS name and its placement's processor, in time order per Module-Task: a job's
events wait until a later job of the same Module-Task has been recorded (its release is later
than anything still to come) and until the run's clock has reached them (the plant server may
be behind the controller's wall clock); the rest go at the end of the run, those after it
dropped. An aborted job (its Module-Task killed) has no ``on_finish``, as in the executive.
"""

from __future__ import annotations

import heapq
from typing import Any

from orccad_app.executive.hooks import Hooks
from orccad_app.sil.generate.table import ModuleTable
from orccad_app.sil.realtime.shared import JobRecord, JobRecords

__all__ = ["JobTrace"]

_RELEASE, _START, _OVERRUN, _COMPUTE_END, _FINISH = range(5)
"""Kinds of event (their order breaks ties at one instant within a record)."""


class JobTrace:
    """The job records of a real-time run, handed to ``hooks`` (see the module docstring).

    :param hooks: the run's observers' callbacks (updated in place when one is added).
    :param table: the controller's module table (names and processors by index).
    """

    def __init__(self, hooks: Hooks, table: ModuleTable) -> None:
        self._hooks = hooks
        self._names = [entry.name for entry in table.entries]
        self._processors = [table.processors[entry.processor] for entry in table.entries]
        self._held: list[list[tuple[int, int, int, JobRecord]]] = [[] for _ in table.entries]
        """Per Module-Task, a heap of events ``(t_ns, order, kind, record)`` not yet handed
        on."""
        self._settled = [-1] * len(table.entries)
        """Per Module-Task, the release of its latest job recorded: no event still to come
        is earlier [ns]."""
        self._order = 0
        self.lost = 0
        """Job records overwritten in the ring before the plant server read them."""

    @property
    def wanted(self) -> bool:
        """Whether an observer listens to the jobs' life cycle (a trace)."""
        hooks = self._hooks
        return bool(hooks.on_release or hooks.on_start or hooks.on_compute_end
                    or hooks.on_finish or hooks.on_overrun)

    def hand(self, batch: JobRecords, now_ns: int, end: bool = False) -> None:
        """Take ``batch`` and hand on the events held up to ``now_ns`` (the run's instant: a
        plant server behind the wall clock holds the controller's later jobs back) that no
        later record can precede; at the run's ``end``, every event up to ``now_ns``, the
        later ones dropped."""
        self.lost += batch.lost
        settled = self._settled
        for record in batch.records:
            self._hold(record)
            if not record.overrun:
                settled[record.module] = record.release_ns
        for m, held in enumerate(self._held):
            if held:
                self._emit(m, now_ns if end else min(settled[m], now_ns), drop_after=end)

    def _hold(self, record: JobRecord) -> None:
        held = self._held[record.module]
        if record.overrun:
            events = [(record.release_ns, _OVERRUN)]
        else:
            events = [(t_ns, kind) for t_ns, kind in (
                (record.release_ns, _RELEASE), (record.start_ns, _START),
                (record.compute_end_ns, _COMPUTE_END), (record.finish_ns, _FINISH)) if t_ns >= 0]
        for t_ns, kind in events:
            self._order += 1
            heapq.heappush(held, (t_ns, self._order, kind, record))

    def _emit(self, m: int, until_ns: int, drop_after: bool) -> None:
        held, name, processor = self._held[m], self._names[m], self._processors[m]
        hooks = self._hooks
        while held and held[0][0] <= until_ns:
            t_ns, _, kind, record = heapq.heappop(held)
            job = record.job
            if kind == _RELEASE:
                _call(hooks.on_release, t_ns, name, job)
            elif kind == _START:
                _call(hooks.on_start, t_ns, name, job, processor)
            elif kind == _COMPUTE_END:
                _call(hooks.on_compute_end, t_ns, name, job, processor)
            elif kind == _FINISH:
                _call(hooks.on_finish, t_ns, name, job, record.finish_ns - record.release_ns,
                      record.missed)
            else:
                _call(hooks.on_overrun, t_ns, name, job)
        if drop_after:
            held.clear()


def _call(listeners: list[Any], *args: Any) -> None:
    for hook in listeners:
        hook(*args)
