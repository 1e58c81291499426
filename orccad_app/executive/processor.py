"""A simulated processor: runs ready Module-Task jobs preemptively under a scheduler.

Execution model:

- a job that becomes ready (its inputs read) joins the ready list and asks for a *dispatch*,
  an event of class ``DISPATCH`` at the same instant, so that every job that becomes ready at
  an instant is considered together;
- dispatch gives the processor to the most urgent ready job; it preempts the running job only
  if strictly more urgent (the preempted job keeps its remaining execution time);
- every time a job is given the processor (first start or resumption) the context-switch
  overhead ``context_switch_ns`` is added to its remaining demand (preemptible like the rest);
- a job's ``compute`` runs in Python when it first gets the processor; when its remaining demand
  reaches zero it leaves the processor and writes its outputs (which may block: a blocked job
  does not hold the processor).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from orccad_app.diagnostics import OrccadError
from orccad_app.executive.kernel import EventClass, Kernel
from orccad_app.executive.scheduler import Scheduler, make_scheduler

if TYPE_CHECKING:
    from orccad_app.executive.job import Job
    from orccad_app.executive.hooks import Hooks

__all__ = ["Processor", "ProcessorStats"]

_FINISH = EventClass.FINISH


@dataclass(slots=True)
class ProcessorStats:
    """Counters of one processor.

    :param busy_ns: time spent running jobs, context switches included [ns].
    :param context_switches: times a job was given the processor.
    :param preemptions: times a running job was preempted.
    :param elapsed_ns: simulated time covered [ns].
    """

    busy_ns: int = 0
    context_switches: int = 0
    preemptions: int = 0
    elapsed_ns: int = 0

    @property
    def load(self) -> float:
        """Busy fraction of the elapsed time, in [0, 1]."""
        return self.busy_ns / self.elapsed_ns if self.elapsed_ns else 0.0


class Processor:
    """A processor with its scheduler.

    :param name: identifier, as used by ``ModuleTask.processor``.
    :param scheduler: ``"fp"`` (fixed-priority preemptive, default), ``"edf"``, or a
        :class:`~orccad_app.executive.scheduler.Scheduler`.
    :param context_switch_ns: overhead each time a job is given the processor [ns].
    """

    def __init__(self, name: str, scheduler: str | Scheduler = "fp",
                 context_switch_ns: int = 0) -> None:
        if not isinstance(context_switch_ns, int) or context_switch_ns < 0:
            raise OrccadError(f"processor '{name}': context_switch_ns must be an integer >= 0, "
                              f"got {context_switch_ns!r}")
        self.name = name
        self.scheduler = make_scheduler(scheduler)
        self.context_switch_ns = context_switch_ns
        self.stats = ProcessorStats()
        self.running: Job | None = None
        self._ready: list[Job] = []
        self._run_start = 0
        self._busy_mark = 0
        self._finish_entry: list | None = None
        self._dispatch_pending = False
        self._kernel: Kernel  # set by attach(), before the run
        self._hooks: Hooks

    def attach(self, kernel: Kernel, hooks: Hooks) -> None:
        """Bind to a simulation's kernel and observer hooks (done by the Simulation)."""
        self._kernel = kernel
        self._hooks = hooks

    # -- jobs entering and leaving -----------------------------------------------------------

    def make_ready(self, job: Job) -> None:
        """``job`` has read its inputs: it competes for the processor from now."""
        job.key = self.scheduler.key(job)
        self._ready.append(job)
        self.request_dispatch()

    def abort(self, job: Job) -> None:
        """Remove a killed job, running or ready."""
        if job is self.running:
            self._account()
            self._kernel.cancel(self._finish_entry)
            self.running = None
            self.request_dispatch()
        elif job in self._ready:
            self._ready.remove(job)

    def request_dispatch(self) -> None:
        """Ask for a scheduling decision at the current instant."""
        if not self._dispatch_pending and self._ready:
            self._dispatch_pending = True
            self._kernel.defer(self._dispatch)  # class DISPATCH, now (Kernel.defer)

    # -- scheduling --------------------------------------------------------------------------

    def _dispatch(self, _: object) -> None:
        self._dispatch_pending = False
        ready = self._ready
        if not ready:
            return
        best = min(ready, key=_job_key) if len(ready) > 1 else ready[0]
        running = self.running
        if running is not None:
            if not best.key < running.key:
                return
            self._preempt(running)
        ready.remove(best)
        self._give(best)

    def _preempt(self, job: Job) -> None:
        now = self._kernel.now
        job.remaining_ns -= now - self._run_start
        self._account()
        self._kernel.cancel(self._finish_entry)
        self.running = None
        self.stats.preemptions += 1
        job.runtime.stats.preemptions += 1
        self._ready.append(job)
        for hook in self._hooks.on_preempt:
            hook(now, job.runtime.name, job.index, self.name)

    def _give(self, job: Job) -> None:
        kernel = self._kernel
        now = kernel.now
        self.running = job
        self._run_start = now
        self._busy_mark = now
        self.stats.context_switches += 1
        job.remaining_ns += self.context_switch_ns
        if job.start_ns < 0:
            job.start_ns = now
            for hook in self._hooks.on_start:
                hook(now, job.runtime.name, job.index, self.name)
            job.runtime.compute(job)
        else:
            for hook in self._hooks.on_resume:
                hook(now, job.runtime.name, job.index, self.name)
        self._finish_entry = kernel.schedule(now + job.remaining_ns, _FINISH, self._complete, job)

    def _complete(self, job: Job) -> None:
        self._account()
        job.remaining_ns = 0
        self.running = None
        self._finish_entry = None
        self.request_dispatch()
        for hook in self._hooks.on_compute_end:
            hook(self._kernel.now, job.runtime.name, job.index, self.name)
        job.runtime.compute_done(job)

    def _account(self) -> None:
        self.stats.busy_ns += self._kernel.now - self._busy_mark
        self._busy_mark = self._kernel.now

    def close(self, now_ns: int) -> None:
        """Bring the statistics up to ``now_ns`` (end of a run segment)."""
        if self.running is not None:
            self._account()
        self.stats.elapsed_ns = now_ns


def _job_key(job: Job) -> tuple:
    return job.key
