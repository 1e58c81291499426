"""Scheduling policies of a simulated processor.

A policy orders ready jobs by a *key* computed once per job (smaller is more urgent); the
processor runs the job with the smallest key and a newly ready job preempts the running one only
if its key is strictly smaller.

- :class:`FixedPriority` (default): key ``(priority, release_ns, sequence)``; 1 is the highest
  priority; equal priorities run in release order (FIFO) and never preempt each other.
- :class:`EarliestDeadlineFirst`: key ``(absolute deadline, priority, release_ns, sequence)``;
  equal deadlines fall back to the fixed priority, then release order.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from orccad_app.diagnostics import OrccadError

if TYPE_CHECKING:
    from orccad_app.executive.job import Job

__all__ = ["Scheduler", "FixedPriority", "EarliestDeadlineFirst", "make_scheduler"]


class Scheduler:
    """A scheduling policy: :meth:`key` orders ready jobs."""

    name = "abstract"

    def key(self, job: Job) -> tuple:
        """The job's urgency key; smaller runs first."""
        raise NotImplementedError


class FixedPriority(Scheduler):
    """Fixed-priority preemptive scheduling (rate-monotonic when priorities follow periods)."""

    name = "fp"

    def key(self, job: Job) -> tuple:
        return (job.runtime.priority, job.release_ns, job.seq)


class EarliestDeadlineFirst(Scheduler):
    """Preemptive earliest-deadline-first scheduling."""

    name = "edf"

    def key(self, job: Job) -> tuple:
        return (job.deadline_ns, job.runtime.priority, job.release_ns, job.seq)


_POLICIES = {"fp": FixedPriority, "edf": EarliestDeadlineFirst}


def make_scheduler(policy: str | Scheduler) -> Scheduler:
    """A scheduler from its name, ``fp`` or ``edf`` (a :class:`Scheduler` passes through)."""
    if isinstance(policy, Scheduler):
        return policy
    try:
        return _POLICIES[policy]()
    except KeyError:
        raise OrccadError(f"unknown scheduler {policy!r}: expected 'fp' or 'edf'") from None
