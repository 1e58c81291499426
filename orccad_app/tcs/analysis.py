"""Utilization and fixed-priority response times of *independent* Module-Tasks.

(The schedulability of a whole TCS as the executive runs it — protocol blocking, EDF, the bus
— is :func:`orccad_app.tcs.schedulability.analyse_timing`.)

**Response-time analysis** (Joseph & Pandya; Audsley et al.) for the fixed-priority preemptive
scheduler of :mod:`orccad_app.executive.scheduler`, per processor:

.. math::

    R_i = B_i + C'_i + \\sum_{j \\in hp(i)} \\lceil R_i / T_j \\rceil \\, C'_j,
    \\qquad C'_k = C_k + 2\\,c_{cs}

iterated from :math:`R_i = B_i + C'_i` to a fixed point, or until :math:`R_i` exceeds the deadline
:math:`D_i` (unschedulable). :math:`hp(i)` holds the other Module-Tasks of the same processor whose
priority number is lower *or equal* (equal priorities interfere both ways: conservative).
:math:`c_{cs}` is the processor's context-switch overhead, charged twice per job (its own dispatch
and the resumption of the job it preempts, the executive's model); :math:`B_i` is a blocking term
the caller may give per Module-Task (the protocols' blocking is not derived: the analysis assumes
independent tasks). With :math:`c_{cs} = 0`, :math:`B_i = 0`, deadlines within periods and all
tasks released together, the analysis is exact: the executive's worst simulated response equals
:math:`R_i` (the test suite checks it).
"""

from __future__ import annotations

from collections import defaultdict
from dataclasses import dataclass
from typing import Iterable, Mapping

from orccad_app.tcs.module_task import ModuleTask

__all__ = ["ResponseTime", "utilization", "response_time_analysis"]


@dataclass(frozen=True, slots=True)
class ResponseTime:
    """Result of the analysis for one Module-Task.

    :param module: its name.
    :param processor: its processor.
    :param response_ns: worst-case response time [ns], ``None`` when it exceeds the deadline.
    :param deadline_ns: relative deadline [ns].
    """

    module: str
    processor: str
    response_ns: int | None
    deadline_ns: int

    @property
    def schedulable(self) -> bool:
        """Whether the worst-case response meets the deadline."""
        return self.response_ns is not None


def utilization(tasks: Iterable[ModuleTask]) -> dict[str, float]:
    """Per-processor utilization :math:`U = \\sum C_i / T_i`, processors in first-seen order."""
    loads: dict[str, float] = {}
    for task in tasks:
        loads[task.processor] = loads.get(task.processor, 0.0) + task.wcet_ns / task.period_ns
    return loads


def _response(task: ModuleTask, higher: list[ModuleTask], switch_ns: int,
              blocking_ns: int) -> int | None:
    cost = task.wcet_ns + 2 * switch_ns
    demand = [(other.period_ns, other.wcet_ns + 2 * switch_ns) for other in higher]
    response = blocking_ns + cost
    while response <= task.deadline_ns:
        following = blocking_ns + cost + sum(-(-response // period) * c for period, c in demand)
        if following == response:
            return response
        response = following
    return None


def response_time_analysis(tasks: Iterable[ModuleTask],
                           context_switch_ns: Mapping[str, int] | int = 0,
                           blocking_ns: Mapping[str, int] | None = None
                           ) -> dict[str, ResponseTime]:
    """Worst-case response time of every Module-Task under fixed-priority preemption.

    :param tasks: the Module-Tasks (any processors).
    :param context_switch_ns: overhead per context switch [ns], one figure for all processors
        or a mapping processor name -> [ns].
    :param blocking_ns: optional blocking term :math:`B_i` per Module-Task name [ns].
    :returns: one :class:`ResponseTime` per Module-Task, by name, in input order.
    """
    tasks = list(tasks)
    by_processor: dict[str, list[ModuleTask]] = defaultdict(list)
    for task in tasks:
        by_processor[task.processor].append(task)
    results: dict[str, ResponseTime] = {}
    for task in tasks:
        if isinstance(context_switch_ns, Mapping):
            switch = context_switch_ns.get(task.processor, 0)
        else:
            switch = context_switch_ns
        higher = [other for other in by_processor[task.processor]
                  if other is not task and other.priority <= task.priority]
        blocking = (blocking_ns or {}).get(task.name, 0)
        response = _response(task, higher, switch, blocking)
        results[task.name] = ResponseTime(task.name, task.processor, response, task.deadline_ns)
    return results
