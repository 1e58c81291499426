"""Schedulability of a whole TCS as the executive runs it: processors (fixed priority or EDF,
context switches), protocol blocking and the bus, solved together.

The pieces (each module documents its own bounds):

- :mod:`~orccad_app.tcs.protocol_blocking`: how long a read or a write can wait, and the rate
  mismatches that make a Module-Task overrun *by construction*;
- :mod:`~orccad_app.tcs.processor_demand`: fixed-priority response times and EDF's
  processor-demand test with release jitter (read waits are jitter);
- :mod:`~orccad_app.tcs.bus_delay`: the FIFO bus's worst delay per message class.

They depend on each other (a consumer's wait depends on its producer's response, which depends
on the bus, whose load jitter depends on the responses), so the analysis iterates from the
independent-task figures to the least fixed point; every term only grows. A Module-Task whose
bound passes its deadline or its period (a job still running at its next release makes the
executive skip that release, which no bound here allows) is marked unschedulable and its bounds
are held at ``min(D, T)``, so that the others are still analysed. The rounds have a budget
(:data:`ROUND_BUDGET`); past it, every Module-Task is "not established".

**Safety.** A Module-Task is called schedulable only when its response bound ``R`` satisfies
``R <= D``, ``R <= T``, and ``R < T`` when a write may wait (such a wait can end at the next
release instant, after that release) or the job costs no processor time (it may be dispatched,
and end, after the releases of the instant it is dispatched at). The whole TCS is schedulable
when every Module-Task is; the figures of the others are only valid if that holds. The property
test ``tests/tcs/test_analysis_safety.py`` checks the claim against executive runs;
docs/executive.md reports the pessimism.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Mapping

from orccad_app.tcs.bus_delay import BusModel, MessageClass, bus_delays, message_classes
from orccad_app.tcs.graph import TCS
from orccad_app.tcs.module_task import ModuleTask
from orccad_app.tcs.phasing import Phase, releases_in_window
from orccad_app.tcs.processor_demand import (BudgetExceeded, Load, busy_period_ns,
                                             density_ok, edf_demand_ok, edf_response_ns,
                                             fp_completion_ns,
                                             fp_release_bound_ns, utilization)
from orccad_app.tcs.protocol import Protocol
from orccad_app.tcs.protocol_blocking import (CONSUMER_WAITS_EACH_VALUE, rate_mismatch,
                                              read_done_ns, write_done_ns)

__all__ = ["TaskTiming", "Schedulability", "analyse_timing", "ROUND_BUDGET"]

ROUND_BUDGET = 1_000
"""Rounds of the global fixed point before the analysis gives up (conservatively)."""


@dataclass(frozen=True, slots=True)
class TaskTiming:
    """The analysis of one Module-Task; times after its release [ns].

    :param module: its name.
    :param processor: its processor.
    :param period_ns: period (minimum inter-arrival time when sporadic).
    :param deadline_ns: relative deadline.
    :param read_wait_ns: latest end of its reads (blocking on inputs; release jitter).
    :param compute_end_ns: latest end of its compute phase.
    :param response_ns: latest end of its writes (the response time); ``None`` when no bound.
    :param problem: why it is not schedulable, ``None`` when it is.
    """

    module: str
    processor: str
    period_ns: int
    deadline_ns: int
    read_wait_ns: int
    compute_end_ns: int
    response_ns: int | None
    problem: str | None = None

    @property
    def write_wait_ns(self) -> int:
        """Latest time its writes wait after the compute phase [ns]."""
        if self.response_ns is None:
            return 0
        return self.response_ns - self.compute_end_ns

    @property
    def schedulable(self) -> bool:
        return self.problem is None


@dataclass(frozen=True, slots=True)
class Schedulability:
    """The analysis of a TCS.

    :param scheduler: ``fp`` or ``edf``.
    :param tasks: per Module-Task, in TCS order.
    :param messages: the bus's message classes with their worst delays.
    :param bus_busy_ns: the bus's longest busy period [ns] (``None`` when overloaded).
    :param notes: what the analysis assumed or gave up on.
    """

    scheduler: str
    tasks: dict[str, TaskTiming]
    messages: list[MessageClass] = field(default_factory=list)
    bus_busy_ns: int | None = 0
    notes: list[str] = field(default_factory=list)

    @property
    def ok(self) -> bool:
        """Every Module-Task meets its deadlines (and no bound was given up on)."""
        return all(t.schedulable for t in self.tasks.values())


class _State:
    """The bounds of one round, per Module-Task name [ns]."""

    def __init__(self, tasks: list[ModuleTask], costs: dict[str, int]) -> None:
        self.read = {t.name: 0 for t in tasks}
        self.compute = {t.name: costs[t.name] for t in tasks}
        self.response = dict(self.compute)
        self.attempt: dict[str, int] = {}
        self.read_at: dict[str, int] = {}

    def key(self) -> tuple:
        return (tuple(self.read.values()), tuple(self.compute.values()),
                tuple(self.response.values()), tuple(sorted(self.attempt.items())),
                tuple(sorted(self.read_at.items())))


class _Analysis:
    def __init__(self, tcs: TCS, scheduler: str, switch: Mapping[str, int], bus: BusModel,
                 groups: Mapping[str, int | None] | None) -> None:
        self.tcs = tcs
        self.scheduler = scheduler
        self.tasks = tcs.module_tasks
        self.by_name = {t.name: t for t in self.tasks}
        self.costs = {t.name: t.wcet_ns + 2 * switch.get(t.processor, 0) for t in self.tasks}
        self.phases = {t.name: Phase(t.min_interarrival_ns, t.offset_ns, t.activation,
                                     0 if groups is None else groups.get(t.name, 0))
                       for t in self.tasks}
        self.bus = bus
        self.problems: dict[str, str] = {}
        self.notes: list[str] = []
        self.reads = {t.name: self._links(t, consumer=True) for t in self.tasks}
        self.writes = {t.name: self._links(t, consumer=False) for t in self.tasks}
        self.classes = message_classes(tcs, bus)

    def _links(self, task: ModuleTask, consumer: bool) -> list:
        links = []
        if consumer:
            for port in task.inputs:
                c = self.tcs.feeding(f"{task.name}.{port.name}")
                if c is not None and c.producer_module in self.by_name:
                    links.append(c)
        else:
            for port in task.outputs:
                links += [c for c in self.tcs.connections_from(task.name)
                          if c.producer_port == port.name and c.consumer_module in self.by_name]
        return links

    def cap(self, task: ModuleTask) -> int:
        return min(task.deadline_ns, task.min_interarrival_ns)

    def remote(self, c) -> bool:
        return (self.by_name[c.producer_module].processor
                != self.by_name[c.consumer_module].processor)

    def fail(self, name: str, why: str) -> None:
        self.problems.setdefault(name, why)

    # -- one round -------------------------------------------------------------------------
    # A Module-Task found failing is recorded and its bounds are clamped at min(D, T), so
    # that the others' figures are still computed (assuming it ends by then).

    def round(self, state: _State) -> _State:
        delays = bus_delays(self.classes, state.response, self.bus_limit())
        if delays is None:
            for c in self.classes:
                self.fail(c.sender, f"the bus is overloaded: no bound on its delays "
                                    f"(utilization {c.bus_utilization:.3f})")
            delays = {(c.connection, c.kind): self.bus_limit() for c in self.classes}
        self.delays = delays
        new = _State(self.tasks, self.costs)
        for task in self.tasks:
            self._reads(task, state, new, delays)
        self._processors(state, new)
        for task in self.tasks:
            self._writes(task, state, new, delays)
        return new

    def bus_limit(self) -> int:
        return max(t.min_interarrival_ns for t in self.tasks) * 4

    def _delay(self, delays, c, kind: str) -> int:
        return delays.get((c.label, kind), 0) if self.remote(c) else 0

    def _reads(self, task: ModuleTask, state: _State, new: _State, delays,
               skip: str | None = None) -> int:
        """The read-wait bound of ``task`` (recorded in ``new`` unless ``skip``: then the
        reads from the Module-Task ``skip`` are taken as not waiting)."""
        tau = 0
        cap = self.cap(task)
        for c in self.reads[task.name]:
            producer = self.by_name[c.producer_module]
            if skip is not None:
                if producer.name == skip:
                    continue
            else:
                new.read_at[c.label] = tau
            attempt = state.attempt.get(c.label, state.compute[producer.name])
            done = read_done_ns(tau, c, producer, task, self.phases, attempt,
                                self._delay(delays, c, "data") + self._delay(delays, c, "reply"),
                                self._delay(delays, c, "request"), self.remote(c))
            if skip is None and done is None:
                self.fail(task.name, f"no bound on its read of {c.label}")
            elif skip is None and done is not None and done > cap:
                self.fail(task.name, f"its read of {c.label} can wait beyond its deadline "
                                     f"or its next release")
            tau = cap if done is None else min(done, cap)
        if skip is None:
            new.read[task.name] = tau
        return tau

    def _successors(self, task: ModuleTask) -> set[str]:
        """Module-Tasks of the same processor, period and phase that wait for every write of
        ``task`` they read (``syn/syn``, ``asyn/synF``, local ``asyn/synDF``): their job
        released with ``task``'s is not ready before ``task``'s compute phase ends."""
        waiting: dict[str, bool] = {}
        for c in self.writes[task.name]:
            consumer = self.by_name[c.consumer_module]
            must_wait = (c.protocol in CONSUMER_WAITS_EACH_VALUE
                         and c.protocol is not Protocol.ASYN_SYN
                         and consumer.processor == task.processor
                         and consumer.min_interarrival_ns == task.min_interarrival_ns
                         and self.phases[task.name].locked_with(self.phases[consumer.name]))
            waiting[consumer.name] = waiting.get(consumer.name, False) or must_wait
        return {name for name, must_wait in waiting.items() if must_wait}

    def _predecessor(self, task: ModuleTask) -> tuple[str, bool] | None:
        """The one higher-priority Module-Task of the same processor, period and phase whose
        write ``task`` may wait for, if there is exactly one, and whether ``task`` may also
        go without waiting for it (every such read is ``asyn/syn``: a fresh value)."""
        found: dict[str, bool] = {}
        for c in self.reads[task.name]:
            producer = self.by_name[c.producer_module]
            if (c.protocol in CONSUMER_WAITS_EACH_VALUE and producer.processor == task.processor
                    and producer.priority <= task.priority
                    and producer.min_interarrival_ns == task.min_interarrival_ns
                    and self.phases[task.name].locked_with(self.phases[producer.name])):
                fresh = c.protocol is Protocol.ASYN_SYN
                found[producer.name] = found.get(producer.name, True) and fresh
        return next(iter(found.items())) if len(found) == 1 else None

    def _processors(self, state: _State, new: _State) -> None:
        by_processor: dict[str, list[ModuleTask]] = {}
        for task in self.tasks:
            by_processor.setdefault(task.processor, []).append(task)
        for processor, tasks in by_processor.items():
            # a job of no execution time counts 1 ns: it then ends no later than the bound
            # says even when it is dispatched after same-instant releases (integer time)
            loads = [Load(t.name, max(1, self.costs[t.name]), t.min_interarrival_ns,
                          self.cap(t), new.read[t.name], t.priority) for t in tasks]
            try:
                if self.scheduler == "edf":
                    self._edf(processor, tasks, loads, new)
                else:
                    self._fp(tasks, loads, state, new)
            except BudgetExceeded:
                for t in tasks:
                    self.fail(t.name, f"not established: the analysis of {processor} needs "
                                      f"more steps than its budget (conservatively "
                                      f"unschedulable)")
                    new.compute[t.name] = self.cap(t)

    def _fp(self, tasks: list[ModuleTask], loads: list[Load], state: _State,
            new: _State) -> None:
        for task, load in zip(tasks, loads):
            others = [x for x in loads if x is not load]
            cap = self.cap(task)
            w = fp_completion_ns(load, others, cap - load.jitter_ns)
            ends = [] if w is None else [load.jitter_ns + w]
            bound = self._release_bound(task, load, others, state, new)
            if bound is not None:
                ends.append(bound)
            if not ends:
                self.fail(task.name, "its compute phase can end after its deadline "
                                     "(processor interference)")
                new.compute[task.name] = cap
            else:
                new.compute[task.name] = min(ends)

    def _release_bound(self, task: ModuleTask, load: Load, others: list[Load], state: _State,
                       new: _State) -> int | None:
        """:func:`fp_release_bound_ns` with phases; when ``task`` waits for the job of its
        predecessor released with it, that job is done before ``task`` is ready: it cannot
        interfere (else ``task`` read a fresh value without waiting for it)."""
        phase = self.phases[task.name]
        cap = self.cap(task)

        successors = self._successors(task)

        def counter(excluded: str | None):
            def count(other: Load, end: int) -> int:
                n = releases_in_window(phase, self.phases[other.name],
                                       state.response[other.name], end)
                return n - 1 if other.name == excluded or other.name in successors else n
            return count

        predecessor = self._predecessor(task)
        if predecessor is None:
            return fp_release_bound_ns(load, others, counter(None), cap)
        name, may_skip = predecessor
        waited = fp_release_bound_ns(load, others, counter(name), cap)
        if waited is None or not may_skip:
            return waited
        jitter = self._reads(task, state, new, self.delays, skip=name)
        alone = replace(load, jitter_ns=jitter)
        skipped = fp_release_bound_ns(alone, others, counter(None), cap)
        return None if skipped is None else max(waited, skipped)

    def _edf(self, processor: str, tasks: list[ModuleTask], loads: list[Load],
             new: _State) -> None:
        load = utilization(loads)
        why, busy = None, None
        if load > 1:
            why = f"{processor} is overloaded (utilization {float(load):.3f} > 1)"
        else:
            limit = max(self.cap(t) for t in tasks) * 1024 + sum(x.jitter_ns for x in loads)
            try:
                busy = busy_period_ns(loads, limit)
            except BudgetExceeded:
                busy = None
        if why is None and not density_ok(loads):
            if busy is None:
                why = (f"not established: the busy period of {processor} exceeds the "
                       f"analysis budget (conservatively unschedulable)")
            elif not edf_demand_ok(loads, busy):
                why = f"EDF's processor-demand test fails on {processor}"
        for task, x in zip(tasks, loads):
            if why is not None:
                self.fail(task.name, why)
                new.compute[task.name] = self.cap(task)
                continue
            ends = [x.deadline_ns]
            if busy is not None:
                ends.append(x.jitter_ns + busy)
                response = edf_response_ns(x, [y for y in loads if y is not x], busy)
                if response is not None:
                    ends.append(response)
            new.compute[task.name] = min(ends)

    def _writes(self, task: ModuleTask, state: _State, new: _State, delays) -> None:
        at = new.compute[task.name]
        cap = self.cap(task)
        waits = self.costs[task.name] == 0  # dispatched, it may end after a release instant
        for c in self.writes[task.name]:
            consumer = self.by_name[c.consumer_module]
            new.attempt[c.label] = at
            bound = write_done_ns(at, c, task, consumer, self.phases, state.response[task.name],
                                  new.read_at.get(c.label, 0), self._delay(delays, c, "data"))
            if bound is None:
                self.fail(task.name, f"no bound on its write of {c.label}")
                at = cap
                continue
            at, waits = min(bound.done_ns, cap + 1), waits or bound.may_wait
        if at > cap:
            self.fail(task.name, "its writes can wait beyond its deadline or its next release"
                      if at > new.compute[task.name] else "its response exceeds its deadline")
        elif waits and at >= task.min_interarrival_ns:
            self.fail(task.name, "its job can end at the instant of its next release, after "
                                 "that release (a write waiting for a read, or no execution "
                                 "time): the release would be skipped")
        new.response[task.name] = min(at, cap)


def analyse_timing(tcs: TCS, scheduler: str = "fp",
                   context_switch_ns: Mapping[str, int] | int = 0,
                   bus: BusModel | None = None,
                   groups: Mapping[str, int | None] | None = None) -> Schedulability:
    """The schedulability of ``tcs`` under ``scheduler`` (``fp`` or ``edf``, every processor).

    :param context_switch_ns: overhead per context switch [ns], one figure or per processor.
    :param bus: transfer times of the bus between processors.
    :param groups: Module-Task name -> activation stage (see
        :class:`~orccad_app.tcs.phasing.Phase`); default: all activated together.
    """
    if scheduler not in ("fp", "edf"):
        raise ValueError(f"unknown scheduler {scheduler!r}")
    switch = context_switch_ns if isinstance(context_switch_ns, Mapping) else {
        t.processor: context_switch_ns for t in tcs.module_tasks}
    analysis = _Analysis(tcs, scheduler, switch, bus or BusModel(), groups)
    for c in tcs.connections:
        if c.producer_module in analysis.by_name and c.consumer_module in analysis.by_name:
            producer, consumer = analysis.by_name[c.producer_module], analysis.by_name[
                c.consumer_module]
            mismatch = rate_mismatch(c, producer, consumer, analysis.phases)
            if mismatch is not None:
                analysis.fail(mismatch.module, "unschedulable by construction: "
                              + mismatch.reason)
    state = _State(analysis.tasks, analysis.costs)
    analysis.delays = {}
    if analysis.tasks:
        for _ in range(ROUND_BUDGET):
            new = analysis.round(state)
            if new.key() == state.key():
                break
            state = new
        else:
            analysis.notes.append("the fixed point did not converge within its budget: "
                                  "conservatively unschedulable")
            for t in analysis.tasks:
                analysis.fail(t.name, "not established (budget)")
    return _result(analysis, state)


def _result(analysis: _Analysis, state: _State) -> Schedulability:
    tasks = {}
    for t in analysis.tasks:
        problem = analysis.problems.get(t.name)
        tasks[t.name] = TaskTiming(t.name, t.processor, t.min_interarrival_ns, t.deadline_ns,
                                   state.read[t.name], state.compute[t.name],
                                   None if problem else state.response[t.name], problem)
    if analysis.problems and len(analysis.problems) < len(analysis.tasks):
        analysis.notes.append("the other Module-Tasks' figures assume that the failing ones "
                              "end by their deadlines; they do not hold otherwise")
    messages = [m.with_delay(analysis.delays.get((m.connection, m.kind)))
                for m in analysis.classes]
    busy = max((m.delay_ns for m in messages if m.delay_ns is not None), default=0)
    return Schedulability(analysis.scheduler, tasks, messages, busy, analysis.notes)
