"""Dynamic deadlock detection: a cycle in the wait-for graph of blocked jobs.

Each blocked job waits for at most one Module-Task (``job.waits_for``, set by its channel):
the one whose next read or write alone can release it. A job blocked on the bus waits for
nobody. Every time a job blocks, the executive follows ``waits_for`` from it through Module-Tasks
whose current job is blocked too; coming back to the first job means none of them can ever
proceed (a Module-Task with an unfinished job skips its releases), so the run stops with
:class:`DeadlockError`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from orccad_app.diagnostics import OrccadError
from orccad_app.executive.job import BLOCKED

if TYPE_CHECKING:
    from orccad_app.executive.job import Job

__all__ = ["DeadlockError", "wait_cycle", "describe_cycle"]


class DeadlockError(OrccadError):
    """Module-Tasks are blocked on each other; :attr:`cycle` lists ``module.port`` per job."""

    exit_status = 1

    def __init__(self, message: str, cycle: tuple[str, ...], time_ns: int) -> None:
        super().__init__(message)
        self.cycle = cycle
        self.time_ns = time_ns


def wait_cycle(job: Job) -> list[Job] | None:
    """The blocked jobs forming a wait cycle through ``job``, in wait order, or ``None``."""
    chain = [job]
    current = job
    while True:
        partner = current.waits_for
        if partner is None:
            return None
        following = partner.job
        if following is None or following.phase != BLOCKED:
            return None
        if following is job:
            return chain
        if following in chain:
            return None
        chain.append(following)
        current = following


def describe_cycle(cycle: list[Job], now_ns: int) -> DeadlockError:
    """A :class:`DeadlockError` naming each blocked ``module.port`` and whom it waits for."""
    parts = []
    for job in cycle:
        operation = "read" if job.start_ns < 0 else "write"
        parts.append(f"{job.runtime.name}.{job.blocked_port} ({operation}, "
                     f"{job.blocked_protocol}) waits for "
                     f"{job.waits_for.name if job.waits_for is not None else '?'}")
    ports = tuple(f"{job.runtime.name}.{job.blocked_port}" for job in cycle)
    message = f"deadlock at t = {now_ns} ns: " + "; ".join(parts)
    return DeadlockError(message, ports, now_ns)
