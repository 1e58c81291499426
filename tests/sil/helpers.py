"""Runs of one mission through the run façade, in the executive or in SIL, compared on their
reports."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from orccad_app.mission.plan import plan_mission
from orccad_app.pipeline import load, select_mission
from orccad_app.session import ControllerOptions, Execution, RunOptions, RunSession

MISSIONS = Path(__file__).resolve().parents[2] / "missions"


def plan_of(file: str, mission: str | None = None):
    """The plan of ``mission`` of shipped ``file``."""
    source = load(str(MISSIONS / file))
    return plan_mission(source, select_mission(source, mission))


def session_of(file: str, mission: str | None = None,
               execution: Execution = Execution.SIMULATED, heartbeat_s: float | None = None,
               **options: Any) -> RunSession:
    """The session of ``mission`` of shipped ``file`` (``options``: RunOptions fields), its
    Module-Tasks run as ``execution`` says (a controller process with ``heartbeat_s``)."""
    source = load(str(MISSIONS / file))
    controller = ControllerOptions(file, None, heartbeat_s) if heartbeat_s else \
        ControllerOptions(file)
    return RunSession(source, select_mission(source, mission),
                      RunOptions(execution=execution, controller=controller, **options))


def report(data: Any) -> dict:
    """The run's JSON report (of a RunReport) without its wall-clock time."""
    data = data.as_dict()
    data.pop("wall_time_s")
    return data


def executive_report(file: str, mission: str | None = None, **options: Any) -> dict:
    """``orccad run``'s report of ``mission`` of ``file``."""
    return report(session_of(file, mission, **options).execute())


def sil_report(file: str, mission: str | None = None, mode: Execution = Execution.LOCKSTEP,
               **options: Any) -> dict:
    """``orccad sil``'s report (without the controller's section) of ``mission`` of
    ``file``; the controller process is gone when it returns."""
    session = session_of(file, mission, mode, **options)
    controller = session.backend.controller
    assert controller.alive
    got = report(session.execute())
    assert not controller.alive
    return got
