"""What the parts of a run share: the kernel, the observers' hooks, the deadlock check.

The :class:`~orccad_app.executive.simulation.Simulation` makes one :class:`RunContext` and
hands it to its Module-Task runtimes (and, through them, to the channels), so that no part
reaches back into the simulation.
"""

from __future__ import annotations

from dataclasses import dataclass

from orccad_app.executive.deadlock import describe_cycle, wait_cycle
from orccad_app.executive.hooks import Hooks
from orccad_app.executive.job import Job
from orccad_app.executive.kernel import Kernel

__all__ = ["RunContext"]


@dataclass(frozen=True)
class RunContext:
    """The shared state of one run.

    :param kernel: the discrete-event kernel (time, events, random streams).
    :param hooks: the observers' callbacks.
    """

    kernel: Kernel
    hooks: Hooks

    def check_deadlock(self, job: Job) -> None:
        """Raise :class:`~orccad_app.executive.deadlock.DeadlockError` if ``job`` closes a
        wait cycle (called whenever a job blocks)."""
        cycle = wait_cycle(job)
        if cycle is None:
            return
        error = describe_cycle(cycle, self.kernel.now)
        for hook in self.hooks.on_deadlock:
            hook(self.kernel.now, error.cycle)
        raise error
