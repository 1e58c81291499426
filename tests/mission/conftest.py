"""Fixtures for mission-layer tests: plans of plan-language texts and of the shipped missions,
one run of missions/arm_pid.orc."""

from __future__ import annotations

import shutil

import pytest

ROOT = __import__("pathlib").Path(__file__).resolve().parents[2]

HOLD_TASK = """
robot arm : arm3dof;

robottask Hold(kp: float = 400.0) on arm {
    duration 0.2 s;
    task_function joint_tracking(trajectory = constant(value = [0.0, 0.0, 0.0]));
    law pid(kp = kp, kv = 40.0);
    module traj : trajectory  period 1 ms wcet 0.1 ms on cpu0 priority 2;
    module ctrl : control_law period 1 ms wcet 0.3 ms on cpu0 priority 1;
    connect traj.qd     -> ctrl.qd;
    connect traj.qd_dot -> ctrl.qd_dot;
    connect arm.q       -> ctrl.q;
    connect arm.qdot    -> ctrl.qdot;
    connect ctrl.tau    -> arm.tau;
%s
}
"""
"""A Robot-Task holding the arm at 0 for 0.2 s; ``%s`` takes extra clauses."""


def _plan_text(tmp_path, text: str, mission: str | None = None):
    """The :class:`MissionPlan` of a plan written to a file under ``tmp_path``."""
    from orccad_app.mission.plan import plan_mission
    from orccad_app.pipeline import load, select_mission

    path = tmp_path / "mission.orc"
    path.write_text(text, encoding="utf-8")
    source = load(path)
    return plan_mission(source, select_mission(source, mission))


def _plan_file(path, replacements: dict[str, str] | None = None, tmp_path=None):
    """The plan of a mission file of the repository, optionally edited (text replaced)."""
    from orccad_app.mission.plan import plan_mission
    from orccad_app.pipeline import load, select_mission

    path = ROOT / path
    if replacements:
        text = path.read_text(encoding="utf-8")
        for old, new in replacements.items():
            assert old in text, old
            text = text.replace(old, new)
        if (path.parent / "lib").is_dir():  # the sub-missions it imports, beside the copy
            shutil.copytree(path.parent / "lib", tmp_path / "lib", dirs_exist_ok=True)
        return _plan_text(tmp_path, text)
    source = load(path)
    return plan_mission(source, select_mission(source, None))


@pytest.fixture(scope="session")
def pid_run():
    """One run of missions/arm_pid.orc (seed 0): ``(plan, result)``."""
    from orccad_app.mission.run import MissionRun

    plan = _plan_file("missions/arm_pid.orc")
    return plan, MissionRun(plan).run()


@pytest.fixture
def plan_text(tmp_path):
    """``plan_text(text, mission=None)``: the plan of a plan-language text."""
    return lambda text, mission=None: _plan_text(tmp_path, text, mission)


@pytest.fixture
def plan_file(tmp_path):
    """``plan_file(path, {old: new})``: the plan of a repository mission, text edited."""
    return lambda path, replacements=None: _plan_file(path, replacements, tmp_path)


@pytest.fixture
def hold_task():
    """The text of the ``Hold`` Robot-Task, ``%s`` for extra clauses."""
    return HOLD_TASK
