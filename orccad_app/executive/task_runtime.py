"""The running instance of a Module-Task: releases, reads, compute, writes (docs/design.md, *The timed executive*).

Job life cycle, all instants in [ns]:

1. **Release** every ``period_ns`` from activation (+ ``offset_ns``); a sporadic Module-Task
   is released by interrupts instead (:mod:`orccad_app.executive.sporadic`). If the previous job is
   still unfinished the release is *skipped* and counted as an overrun (the unfinished job is
   a deadline miss when it finishes late): a Module-Task never has two jobs at once.
2. **Read** the inputs in port order at the release instant; a protocol may block the job,
   which then reads the remaining ports when released.
3. **Compute**: the job competes for its processor; when it first gets it, the Python
   ``compute(t_s, inputs)`` runs at once (``t_s`` is that instant in [s]); its execution time
   (``wcet_ns``, or drawn uniformly in ``[bcet_ns, wcet_ns]``) then occupies the processor,
   preemptibly.
4. **Write** the outputs in port order when the execution time is consumed: only then are the
   results visible (the execution time is an input/output delay). A protocol may block a write.
   A written event port whose value is neither ``None`` nor ``False`` is a signal.

Execution times with ``bcet_ns`` come from the stream ``mt/<name>/duration`` of the run's seed,
drawn in blocks of 256 with ``Generator.integers(bcet, wcet, endpoint=True)``.
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import TYPE_CHECKING, Any

from orccad_app.diagnostics import OrccadError
from orccad_app.executive.block import BLOCK
from orccad_app.executive.context import RunContext
from orccad_app.executive.delays import jitter_draws
from orccad_app.executive.job import (ABORTED, BLOCKED, DONE, READING, READY, WAKING, WRITING,
                                      Job, TaskStats)
from orccad_app.executive.kernel import EventClass
from orccad_app.executive.processor import Processor
from orccad_app.tcs.module_task import Activation, ModuleTask

if TYPE_CHECKING:
    from orccad_app.executive.channel import Channel

__all__ = ["ModuleTaskRuntime", "ComputeError"]

_RELEASE = EventClass.RELEASE
_WAKE = EventClass.WAKE
_DRAW_BLOCK = 256


class ComputeError(OrccadError):
    """A Module-Task's compute object raised or returned something that is not a dict."""


class ModuleTaskRuntime:
    """Runs one Module-Task inside a :class:`~orccad_app.executive.simulation.Simulation`.

    :attr:`reads` lists ``(port, channel)`` per connected input in port order;
    :attr:`writes` lists ``(port, is_event, channel)`` in port order, where a ``None`` channel
    marks the port's own write (observers, signals) before its connections.
    """

    def __init__(self, context: RunContext, task: ModuleTask, processor: Processor) -> None:
        self.context = context
        self.task = task
        self.name = task.name
        self.priority = task.priority
        self.processor = processor
        self.reads: list[tuple[str, Channel]] = []
        self.writes: list[tuple[str, bool, Channel | None]] = []
        self.stats = TaskStats()
        self.active = False
        self.job: Job | None = None
        self._kernel = context.kernel
        self._hooks = context.hooks
        self._release_entry: list | None = None
        self._write_listeners: list[list] = []
        self._count = 0
        self._draws: list[int] = []
        self._rng = None
        if task.bcet_ns is not None and task.bcet_ns < task.wcet_ns:
            self._rng = context.kernel.stream(f"mt/{task.name}/duration")
        self._jitter: Iterator[int] | None = None
        self._late_entry: list | None = None

    def jitter(self, jitter_ns: int) -> None:
        """Make each periodic release late by a uniform draw in ``[0, jitter_ns]`` (a real
        controller's thread lateness, :mod:`orccad_app.executive.delays`; the period's grid
        kept, the job's response time and deadline counted from its grid instant); call it
        before the run."""
        if jitter_ns > 0 and self.task.activation is not Activation.SPORADIC:
            self._jitter = jitter_draws(self._kernel, self.name, jitter_ns)

    # -- activation --------------------------------------------------------------------------

    def activate(self) -> None:
        """Start releasing jobs now (+ offset); call the compute object's ``init()``."""
        if self.active:
            return
        self.active = True
        init = getattr(self.task.compute, "init", None)
        if callable(init):
            self._call(init)
        if self.task.activation is Activation.SPORADIC:
            return  # released by interrupts (orccad_app/executive/sporadic.py)
        first = self._kernel.now + self.task.offset_ns
        self._release_entry = self._kernel.schedule(first, _RELEASE, self._release)

    def kill(self) -> None:
        """Stop releasing jobs and abort the unfinished one."""
        if not self.active:
            return
        self.active = False
        self._kernel.cancel(self._release_entry)
        self._kernel.cancel(self._late_entry)
        self._late_entry = None
        job = self.job
        if job is not None:
            self.job = None
            self.stats.aborted += 1
            if job.phase == BLOCKED:
                self.stats.blocking_ns += self._kernel.now - job.blocked_since
            job.phase = ABORTED
            self._kernel.cancel(job.wake_entry)
            for _, channel in self.reads:
                channel.cancel(job)
            for _, _, written in self.writes:
                if written is not None:
                    written.cancel(job)
            self.processor.abort(job)

    def set_param(self, name: str, value: Any) -> None:
        """Forward a parameter change to the compute object's ``set_param``."""
        setter = getattr(self.task.compute, "set_param", None)
        if not callable(setter):
            raise OrccadError(f"module-task '{self.name}' has no settable parameters "
                              f"(cannot set '{name}')")
        self._call(setter, name, value)

    # -- job life cycle ----------------------------------------------------------------------

    def _release(self, _: object) -> None:
        kernel = self._kernel
        now = kernel.now
        task = self.task
        self._release_entry = kernel.schedule(now + task.period_ns, _RELEASE, self._release)
        if self._jitter is None:
            self.release_job(now)
        else:
            self._release_late(now, next(self._jitter))

    def _release_late(self, grid_ns: int, late_ns: int) -> None:
        """The release of grid instant ``grid_ns``, ``late_ns`` late; a late release still
        waiting goes first (releases never pass each other)."""
        waiting = self._late_entry
        if waiting is not None:
            self._kernel.cancel(waiting)
            self._late_entry = None
            self.release_job(self._kernel.now, waiting[-1])
        if late_ns == 0:
            self.release_job(grid_ns)
        else:
            self._late_entry = self._kernel.schedule(grid_ns + late_ns, _RELEASE,
                                                     self._released_late, grid_ns)

    def _released_late(self, grid_ns: int) -> None:
        self._late_entry = None
        self.release_job(self._kernel.now, grid_ns)

    def release_job(self, now: int, grid_ns: int | None = None) -> None:
        """Release a job now (a periodic release, or a sporadic one's interrupt); skipped and
        counted as an overrun while the previous job is unfinished. ``grid_ns``: the
        instant the release was due (a late one's), from which its response time and
        deadline count."""
        kernel = self._kernel
        task = self.task
        if self.job is not None:
            self.stats.overruns += 1
            for hook in self._hooks.on_overrun:
                hook(now, self.name, self.job.index)
            return
        index = self._count
        self._count += 1
        duration = task.wcet_ns if self._rng is None else self._duration()
        due = now if grid_ns is None else grid_ns
        job = Job(self, index, kernel._seq, due, due + task.deadline_ns, duration)
        self.job = job
        self.stats.released += 1
        for hook in self._hooks.on_release:
            hook(now, self.name, index)
        self._read(job)

    def _duration(self) -> int:
        bcet = self.task.bcet_ns
        if self._rng is None or bcet is None:
            return self.task.wcet_ns
        if not self._draws:
            block = self._rng.integers(bcet, self.task.wcet_ns, endpoint=True, size=_DRAW_BLOCK)
            self._draws = block.tolist()[::-1]
        return self._draws.pop()

    def _read(self, job: Job) -> None:
        reads = self.reads
        inputs = job.inputs
        on_read = self._hooks.on_read
        op, count = job.op, len(reads)
        while op < count:
            port, channel = reads[op]
            value = channel.read(job)
            if value is BLOCK:
                job.op = op
                self._block(job, port, "read", channel)
                return
            inputs[port] = value
            if on_read:
                now = self._kernel.now
                for hook in on_read:
                    hook(now, self.name, port, value)
            op += 1
        job.phase = READY
        job.op = 0
        self.processor.make_ready(job)

    def _block(self, job: Job, port: str, operation: str, channel: Channel) -> None:
        now = self._kernel.now
        job.phase = BLOCKED
        job.blocked_since = now
        job.blocked_port = port
        job.blocked_protocol = channel.protocol_name
        for hook in self._hooks.on_block:
            hook(now, self.name, port, operation, channel.protocol_name)
        self.context.check_deadlock(job)

    def check_deadlock(self, job: Job) -> None:
        """``job`` just blocked: raise if it closes a wait cycle (the run's check)."""
        self.context.check_deadlock(job)

    def wake(self, job: Job, value: Any = None) -> None:
        """Called by a channel: the blocked operation of ``job`` completes (with ``value``
        for a read); the job resumes at this instant, after the current event."""
        if job.phase != BLOCKED:
            return
        job.phase = WAKING
        job.waits_for = None
        job.wake_value = value
        job.wake_entry = self._kernel.schedule(self._kernel.now, _WAKE, self._resume, job)

    def _resume(self, job: Job) -> None:
        now = self._kernel.now
        job.wake_entry = None
        blocked = now - job.blocked_since
        self.stats.blocking_ns += blocked
        reading = job.start_ns < 0
        for hook in self._hooks.on_unblock:
            hook(now, self.name, job.blocked_port, "read" if reading else "write", blocked)
        if reading:
            job.inputs[job.blocked_port] = job.wake_value
            for hook in self._hooks.on_read:
                hook(now, self.name, job.blocked_port, job.wake_value)
            job.phase = READING
            job.op += 1
            self._read(job)
        else:
            job.phase = WRITING
            job.op += 1
            self._write(job)

    def compute(self, job: Job) -> None:
        """Run the compute object (called by the processor when the job first runs)."""
        obj = self.task.compute
        if obj is None:
            return
        outputs = self._call(obj.compute, self._kernel.now / 1e9, job.inputs)
        if outputs is None:
            return
        if not isinstance(outputs, dict):
            raise ComputeError(f"module-task '{self.name}': compute returned "
                               f"{type(outputs).__name__}, expected a dict of output values")
        job.outputs = outputs

    def _call(self, function: Any, *args: Any) -> Any:
        try:
            return function(*args)
        except OrccadError:
            raise
        except Exception as error:  # user code: report it with the module's name
            raise ComputeError(f"module-task '{self.name}': {function.__name__} raised "
                               f"{type(error).__name__}: {error} "
                               f"(at t = {self._kernel.now} ns)") from error

    def compute_done(self, job: Job) -> None:
        """The execution time is consumed: write the outputs."""
        job.phase = WRITING
        job.op = 0
        self._write(job)

    def _write(self, job: Job) -> None:
        writes = self.writes
        count = len(writes)
        listeners = self._write_listeners
        if len(listeners) != count:
            listeners = self._listen(writes)
        outputs = job.outputs
        on_signal = self._hooks.on_signal
        op = job.op
        while op < count:
            port, is_event, channel = writes[op]
            value = outputs.get(port)
            if value is None or (is_event and value is False):
                op += 1
                continue
            if channel is None:
                wanting = listeners[op]
                if wanting:
                    now = self._kernel.now
                    for hook in wanting:
                        hook(now, self.name, port, value)
                if is_event:
                    now = self._kernel.now
                    for hook in on_signal:
                        hook(now, f"{self.name}.{port}", value)
            elif not channel.write(job, value):
                job.op = op
                self._block(job, port, "write", channel)
                return
            op += 1
        job.op = op
        self._finish(job)

    def _listen(self, writes: list[tuple[str, bool, Channel | None]]) -> list[list]:
        """Per entry of :attr:`writes`, the ``on_write`` listeners of its port's own write
        (empty for connections): lists kept up to date by the hooks."""
        hooks = self._hooks
        self._write_listeners = [hooks.write_listeners(self.name, port) if channel is None
                                 else [] for port, _, channel in writes]
        return self._write_listeners

    def _finish(self, job: Job) -> None:
        now = self._kernel.now
        job.phase = DONE
        self.job = None
        stats = self.stats
        response = now - job.release_ns
        stats.completed += 1
        stats.response_sum_ns += response
        if response > stats.response_max_ns:
            stats.response_max_ns = response
        if stats.response_min_ns < 0 or response < stats.response_min_ns:
            stats.response_min_ns = response
        missed = now > job.deadline_ns
        if missed:
            stats.late += 1
        for hook in self._hooks.on_finish:
            hook(now, self.name, job.index, response, missed)

    def close(self, now_ns: int) -> None:
        """Bring the statistics up to ``now_ns`` (end of a run segment)."""
        job = self.job
        self.stats.late_pending = int(job is not None and now_ns > job.deadline_ns)
