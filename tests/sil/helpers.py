"""Runs of one mission in the executive and in lockstep SIL, compared on their reports."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from orccad_app.executive.bus import Bus
from orccad_app.executive.processor import Processor
from orccad_app.mission.plan import plan_mission
from orccad_app.mission.run import MissionRun
from orccad_app.pipeline import load, select_mission
from orccad_app.trace import report_dict

MISSIONS = Path(__file__).resolve().parents[2] / "missions"


def plan_of(file: str, mission: str | None = None):
    source = load(str(MISSIONS / file))
    return plan_mission(source, select_mission(source, mission))


def mission_run(plan, until_s: float | None = None, injections=(), observers=()) -> MissionRun:
    until_ns = int(round((until_s or plan.run_horizon_s(60.0)) * 1e9))
    return MissionRun(plan, until_ns=until_ns, injections=list(injections),
                      processors=[Processor(name) for name in plan.processor_names], bus=Bus(),
                      observers=list(observers))


def report(result: Any) -> dict:
    """The run's JSON report without its wall-clock time."""
    data = report_dict(result, [])
    data.pop("wall_time_s")
    return data
