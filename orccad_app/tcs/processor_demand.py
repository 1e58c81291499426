"""One processor's share of the schedulability analysis: fixed-priority response times and
EDF's processor-demand test, both with release jitter.

A job of Module-Task ``i`` is released every ``T_i`` (at least, if sporadic), becomes ready
at most ``J_i`` later (the time its reads may block: release jitter), and needs
``C'_i = C_i + 2·c_cs`` on the processor (its execution time and two context switches: its own
dispatch and the resumption of the job it preempts, the executive's model).

**Fixed priority** (Audsley et al., with jitter): from readiness the job completes within
:math:`w_i = C'_i + \\sum_{j \\in hp(i)} \\max(1, \\lceil (w_i + J_j)/T_j \\rceil)\\,C'_j`
(``hp`` holds the other Module-Tasks of priority number lower *or equal*: ties interfere both
ways). The caller charges a job of no execution time 1 ns: such a job ends when it is
dispatched, after the releases of that instant, and a 1 ns job's bound covers that.

**EDF** (Spuri; Zhang & Burns' QPA): a job's absolute deadline is its release + ``D_i``; every
deadline is met iff :math:`h(t) = \\sum_j \\max(0, \\lfloor (t + J_j - D_j)/T_j \\rfloor + 1)\\,
C'_j \\le t` for every ``t`` up to the longest busy period ``L``. QPA walks the deadlines down
from ``L`` and stops after few steps; before it, the density test
:math:`\\sum C'_j / \\min(T_j, D_j - J_j) \\le 1` settles most sets at once (and exactly the
implicit-deadline ones without jitter: ``U <= 1``, whatever the hyperperiod). The end of a
job's compute phase is then bounded by Spuri's response time (:func:`edf_response_ns`), by
``J_i + L`` (a job completes within the busy period it is released in) and by ``D_i``.

Both iterations have a **budget** (:data:`ITERATION_BUDGET` steps): a period set that would
need more (a 1 ns period next to a 1 s one at full load) gets the conservative answer
"not established", never "schedulable".
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import Callable

__all__ = ["Load", "ITERATION_BUDGET", "BudgetExceeded", "fp_completion_ns",
           "fp_release_bound_ns", "busy_period_ns",
           "edf_demand_ok", "density_ok", "edf_response_ns", "utilization"]

ITERATION_BUDGET = 100_000
"""Steps an iteration may take before the analysis gives up (conservatively)."""


class BudgetExceeded(Exception):
    """An iteration needed more than :data:`ITERATION_BUDGET` steps."""


@dataclass(frozen=True, slots=True)
class Load:
    """One Module-Task's demand on its processor.

    :param name: the Module-Task.
    :param cost_ns: ``C'`` [ns], context switches included.
    :param period_ns: period or minimum inter-arrival time ``T`` [ns].
    :param deadline_ns: relative deadline ``D`` [ns].
    :param jitter_ns: release jitter ``J`` [ns] (read blocking).
    :param priority: fixed priority (1 highest).
    """

    name: str
    cost_ns: int
    period_ns: int
    deadline_ns: int
    jitter_ns: int
    priority: int


def utilization(loads: list[Load]) -> Fraction:
    """:math:`\\sum C'/T`, exactly."""
    return sum((Fraction(x.cost_ns, x.period_ns) for x in loads), Fraction(0))


def fp_completion_ns(task: Load, others: list[Load], limit_ns: int) -> int | None:
    """``w_i`` of ``task`` under fixed priority [ns] (from readiness to completion), ``None``
    when it exceeds ``limit_ns``. Raises :class:`BudgetExceeded`."""
    higher = [x for x in others if x.priority <= task.priority]
    if utilization(higher + [task]) > 1:
        return None
    w = task.cost_ns + sum(x.cost_ns for x in higher)
    for _ in range(ITERATION_BUDGET):
        if w > limit_ns:
            return None
        following = task.cost_ns + sum(
            max(1, -(-(w + x.jitter_ns) // x.period_ns)) * x.cost_ns for x in higher)
        if following == w:
            return w
        w = following
    raise BudgetExceeded(task.name)


def fp_release_bound_ns(task: Load, others: list[Load], count: Callable[[Load, int], int],
                        limit_ns: int) -> int | None:
    """A second bound on the compute end of ``task`` under fixed priority, from its release
    [ns]: :math:`E = J_i + C'_i + \\sum_{j \\in hp(i)} N_j(E)\\,C'_j`, where ``count(j, E)``
    bounds the jobs of ``j`` that can still run in ``[r, r + E]`` (released after
    ``r - R_j``); with known phases it is much smaller than the jitter bound's for a job
    that waited on a higher-priority producer of its processor (that producer's job is then
    done). ``None`` when it exceeds ``limit_ns``. Raises :class:`BudgetExceeded`."""
    higher = [x for x in others if x.priority <= task.priority]
    end = task.jitter_ns + task.cost_ns
    for _ in range(ITERATION_BUDGET):
        if end > limit_ns:
            return None
        following = task.jitter_ns + task.cost_ns + sum(count(x, end) * x.cost_ns
                                                          for x in higher)
        if following == end:
            return end
        end = following
    raise BudgetExceeded(task.name)


def busy_period_ns(loads: list[Load], limit_ns: int) -> int | None:
    """The longest busy period :math:`L = \\sum \\lceil (L + J_j)/T_j \\rceil C'_j` [ns],
    ``None`` when it exceeds ``limit_ns``. Raises :class:`BudgetExceeded`."""
    if utilization(loads) > 1:
        return None
    length = sum(x.cost_ns for x in loads)
    for _ in range(ITERATION_BUDGET):
        if length > limit_ns:
            return None
        following = sum(max(1, -(-(length + x.jitter_ns) // x.period_ns)) * x.cost_ns
                        for x in loads)
        if following == length:
            return length
        length = following
    raise BudgetExceeded("busy period")


def density_ok(loads: list[Load]) -> bool:
    """EDF's sufficient density test :math:`\\sum C'_j / (D_j - J_j) \\le 1` (deadlines
    taken at most the periods); exact when every ``D_j - J_j`` is the period."""
    total = Fraction(0)
    for x in loads:
        window = min(x.deadline_ns - x.jitter_ns, x.period_ns)
        if window <= 0:
            if x.cost_ns > 0 or window < 0:
                return False
            continue
        total += Fraction(x.cost_ns, window)
    return total <= 1


def _demand(loads: list[Load], t: int) -> int:
    total = 0
    for x in loads:
        jobs = (t + x.jitter_ns - x.deadline_ns) // x.period_ns + 1
        if jobs > 0:
            total += jobs * x.cost_ns
    return total


def _deadline_before(loads: list[Load], t: int) -> int | None:
    """The largest deadline point ``k·T_j + D_j - J_j < t``."""
    best = None
    for x in loads:
        first = x.deadline_ns - x.jitter_ns
        if first < t:
            point = first + (t - 1 - first) // x.period_ns * x.period_ns
            best = point if best is None else max(best, point)
    return best


def edf_demand_ok(loads: list[Load], busy_ns: int) -> bool:
    """The processor-demand test up to the busy period ``busy_ns`` (QPA). Raises
    :class:`BudgetExceeded`."""
    if any(x.deadline_ns - x.jitter_ns < x.cost_ns for x in loads):
        return False
    smallest = min(x.deadline_ns - x.jitter_ns for x in loads)
    t = _deadline_before(loads, busy_ns + 1)
    if t is None:
        return True
    for _ in range(ITERATION_BUDGET):
        demand = _demand(loads, t)
        if demand > t:
            return False
        if demand <= smallest:
            return True
        if demand < t:
            t = demand
        else:
            previous = _deadline_before(loads, t)
            if previous is None:
                return True
            t = previous
    raise BudgetExceeded("processor demand")


def _edf_busy_window(task: Load, others: list[Load], offset: int, start: int,
                     limit_ns: int) -> int | None:
    """Spuri's :math:`w_i(a)`: the longest interval, from the start of a busy period of jobs
    with deadlines at most ``task``'s, that ends with the completion of the job of ``task``
    released ``a = offset`` after its start."""
    own = ((offset + task.jitter_ns) // task.period_ns + 1) * task.cost_ns
    w = max(start, own)
    for _ in range(ITERATION_BUDGET):
        if w > limit_ns:
            return None
        total = own
        for x in others:
            window = offset + task.deadline_ns - x.deadline_ns + x.jitter_ns
            if window < 0:
                continue
            jobs = min(-(-(w + x.jitter_ns) // x.period_ns), window // x.period_ns + 1)
            total += max(jobs, 0) * x.cost_ns
        if total <= w:
            return w
        w = total
    raise BudgetExceeded(task.name)


def edf_response_ns(task: Load, others: list[Load], busy_ns: int,
                    points_budget: int = 20_000) -> int | None:
    """The worst time from a release of ``task`` to the end of its compute phase under EDF
    (Spuri's response-time analysis with jitter) [ns]: the maximum of ``w_i(a) - a`` over the
    offsets ``a`` in ``[-J_i, L)`` where a count changes. Jobs with the same absolute deadline
    count as interfering (the executive breaks such ties by priority). ``None`` when there
    are more offsets than ``points_budget`` (the caller keeps a coarser bound)."""
    offsets: set[int] = set()
    for x in [task, *others]:
        if x is task:
            first = -task.jitter_ns
        else:
            first = x.deadline_ns - x.jitter_ns - task.deadline_ns
        if first < -task.jitter_ns:
            first += -(-(-task.jitter_ns - first) // x.period_ns) * x.period_ns
        count = max(0, (busy_ns - first + x.period_ns - 1) // x.period_ns)
        if len(offsets) + count > points_budget:
            return None
        offsets.update(range(first, busy_ns, x.period_ns))
    worst = task.jitter_ns + task.cost_ns
    for offset in sorted(offsets):
        w = _edf_busy_window(task, others, offset, offset + task.jitter_ns + task.cost_ns,
                             2 * busy_ns + task.jitter_ns + task.cost_ns)
        if w is None:
            return None
        worst = max(worst, w - offset)
    return worst
