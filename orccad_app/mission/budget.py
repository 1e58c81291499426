"""How long a mission run may last, and what it may cost, checked before it is built.

The default simulated-time limit (:data:`DEFAULT_UNTIL_NS`, or the plan's longer horizon:
:func:`run_horizon_s`) and the budget of reactions and Module-Task jobs a run may cost
(:func:`check_run_budget`, checked by :class:`~orccad_app.mission.run.MissionRun` and by
``orccad sil`` before it starts the controller).
"""

from __future__ import annotations

from orccad_app.diagnostics import OrccadError
from orccad_app.mission.plan import MissionPlan

__all__ = ["DEFAULT_UNTIL_NS", "MAX_RUN_EVENTS", "check_run_budget", "run_horizon_s"]

DEFAULT_UNTIL_NS = 60_000_000_000
"""Default simulated-time limit of a run [ns] (60 s)."""

MAX_RUN_EVENTS = 50_000_000
"""Most reactions and Module-Task jobs one run may cost, counted before it starts (every
Module-Task released over the whole horizon, an upper bound): a 1 us period costs about 50 s
and 1.4 GB per simulated second, so the period's gcd alone is no budget."""


def check_run_budget(plan: MissionPlan, until_ns: int) -> None:
    """Refuse a run of ``plan`` up to ``until_ns`` that would cost more than
    :data:`MAX_RUN_EVENTS` reactions and jobs (before any of it is built)."""
    reactions = until_ns // plan.tick_ns if plan.tick_ns else 0
    jobs = sum(until_ns // task.period_ns for task in plan.tcs.module_tasks
               if task.period_ns > 0)
    if reactions + jobs > MAX_RUN_EVENTS:
        fastest = min((task.period_ns for task in plan.tcs.module_tasks), default=0)
        raise OrccadError(
            f"this run would cost up to {reactions + jobs:.3g} reactions and Module-Task jobs "
            f"({until_ns / 1e9:g} s simulated, the fastest period {fastest} ns, reactions every "
            f"{plan.tick_ns} ns): more than the {MAX_RUN_EVENTS:.3g} a run may cost; shorten "
            "--until or lengthen the periods")


def run_horizon_s(plan: MissionPlan, default_s: float) -> float:
    """The default simulated-time limit of ``plan`` [s] (:meth:`MissionPlan.run_horizon_s`)."""
    return plan.run_horizon_s(default_s)
