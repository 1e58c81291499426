"""Jobs of Module-Tasks and their statistics.

A job goes through phases: ``READING`` its inputs in port order (a read may leave it
``BLOCKED``), ``READY`` to run on its processor (running or preempted), then ``WRITING`` its
outputs in port order (a write may leave it ``BLOCKED``), then ``DONE``. A blocked job whose
partner has acted is ``WAKING`` until it resumes, later in the same instant. A killed job is
``ABORTED``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Protocol

__all__ = ["Job", "JobOwner", "TaskStats", "READING", "BLOCKED", "WAKING", "READY", "WRITING", "DONE",
           "ABORTED"]

READING, BLOCKED, WAKING, READY, WRITING, DONE, ABORTED = range(7)


class JobOwner(Protocol):
    """What jobs, processors, schedulers and channels use of the Module-Task running a job
    (:class:`~orccad_app.executive.task_runtime.ModuleTaskRuntime`)."""

    name: str
    priority: int
    stats: TaskStats
    job: Job | None
    """The Module-Task's unfinished job, if any."""
    active: bool
    """Whether the Module-Task is started (its behaviour automaton activated it)."""

    def compute(self, job: Job) -> None:
        """``job`` got its processor for the first time: run the compute object."""

    def compute_done(self, job: Job) -> None:
        """``job``'s execution time is consumed: write its outputs."""

    def wake(self, job: Job, value: Any = None) -> None:
        """A protocol releases the blocked ``job`` (with the value it waited for)."""

    def check_deadlock(self, job: Job) -> None:
        """``job`` just blocked: raise if it closes a wait cycle."""


class Job:
    """One activation of a Module-Task.

    Times are instants in [ns]; ``start_ns`` is -1 until the job first gets its processor.
    """

    __slots__ = ("runtime", "index", "seq", "release_ns", "deadline_ns", "remaining_ns", "key",
                 "start_ns", "phase", "op", "inputs", "outputs", "blocked_since", "blocked_port",
                 "blocked_protocol", "waits_for", "wake_value", "wake_entry")

    def __init__(self, runtime: JobOwner, index: int, seq: int, release_ns: int,
                 deadline_ns: int, duration_ns: int) -> None:
        self.runtime = runtime
        self.index = index
        self.seq = seq
        self.release_ns = release_ns
        self.deadline_ns = deadline_ns
        self.remaining_ns = duration_ns
        self.key: tuple = ()
        self.start_ns = -1
        self.phase = READING
        self.op = 0
        self.inputs: dict[str, Any] = {}
        self.outputs: dict[str, Any] = {}
        self.blocked_since = 0
        self.blocked_port = ""
        self.blocked_protocol = ""
        self.waits_for: JobOwner | None = None
        """While blocked: the Module-Task whose action alone can release this job (``None``
        when the bus or nothing in particular will)."""
        self.wake_value: Any = None
        self.wake_entry: list | None = None

    def __repr__(self) -> str:
        return f"Job({self.runtime.name}#{self.index})"


@dataclass(slots=True)
class TaskStats:
    """Counters of one Module-Task.

    :param released: jobs released.
    :param completed: jobs that wrote all their outputs.
    :param aborted: jobs killed before completing.
    :param overruns: releases skipped because the previous job was unfinished.
    :param late: completed jobs that finished after their absolute deadline.
    :param late_pending: 1 if the unfinished job was past its deadline at the end of the run.
    :param preemptions: times one of its jobs was preempted.
    :param blocking_ns: total time its jobs spent blocked on ports [ns].
    :param response_min_ns: shortest response time (finish - release) [ns], -1 if none.
    :param response_max_ns: longest response time [ns].
    :param response_sum_ns: sum of response times [ns].
    """

    released: int = 0
    completed: int = 0
    aborted: int = 0
    overruns: int = 0
    late: int = 0
    late_pending: int = 0
    preemptions: int = 0
    blocking_ns: int = 0
    response_min_ns: int = -1
    response_max_ns: int = 0
    response_sum_ns: int = 0

    @property
    def deadline_misses(self) -> int:
        """Jobs that finished late, plus an unfinished one already past its deadline."""
        return self.late + self.late_pending

    @property
    def response_mean_ns(self) -> float:
        """Mean response time over completed jobs [ns] (0 if none)."""
        return self.response_sum_ns / self.completed if self.completed else 0.0
