"""Runs of one mission through the run façade, in the executive or in SIL, compared on their
reports."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from orccad_app.mission.plan import plan_mission
from orccad_app.pipeline import load, select_mission
from orccad_app.session import RunOptions, RunSession
from orccad_app.sil.runs import ControllerRuns, SilMode

MISSIONS = Path(__file__).resolve().parents[2] / "missions"


def plan_of(file: str, mission: str | None = None):
    """The plan of ``mission`` of shipped ``file``."""
    source = load(str(MISSIONS / file))
    return plan_mission(source, select_mission(source, mission))


def session_of(file: str, mission: str | None = None, runs: ControllerRuns | None = None,
               **options: Any) -> RunSession:
    """The session of ``mission`` of shipped ``file`` (``options``: RunOptions fields), its
    run made by ``runs`` when given."""
    source = load(str(MISSIONS / file))
    return RunSession(source, select_mission(source, mission),
                      RunOptions(run_factory=runs, **options))


def report(data: Any) -> dict:
    """The run's JSON report (of a RunReport) without its wall-clock time."""
    data = data.as_dict()
    data.pop("wall_time_s")
    return data


def executive_report(file: str, mission: str | None = None, **options: Any) -> dict:
    """``orccad run``'s report of ``mission`` of ``file``."""
    return report(session_of(file, mission, **options).execute())


def sil_report(file: str, mission: str | None = None, mode: SilMode = SilMode.LOCKSTEP,
               **options: Any) -> dict:
    """``orccad sil``'s report (without the controller's section) of ``mission`` of
    ``file``; the controller process is gone when it returns."""
    with ControllerRuns(mode, file) as runs:
        got = report(session_of(file, mission, runs, **options).execute())
        assert runs.controller is not None and runs.controller.alive
    assert not runs.controller.alive
    return got
