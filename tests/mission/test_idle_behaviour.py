"""Issue 15, defect 3: a robot type declares its idle behaviour; the executive holds the robot
with it before, between and after Robot-Tasks, and the trace shows it (docs/robot-tasks.md,
*Idle behaviour*)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from orccad_app.control.robot import IdleBehaviour
from orccad_app.executive import Observer
from orccad_app.mission.run import MissionRun

IDLE_MISSION = """
mission Idle {
    await 0.5 s;
    run Hold();
    await 0.5 s;
}
"""


class _Signals(Observer):
    def __init__(self) -> None:
        self.signals: list[tuple[int, str, object]] = []
        self.plant = None
        self.idle_at: list[np.ndarray] = []

    def on_signal(self, t_ns: int, name: str, value: object) -> None:
        if name.startswith("arm."):
            self.signals.append((t_ns, name, value))
        if name == "arm.idle":
            self.idle_at.append(self.plant.qpos)


def _with_idle(plan, behaviour):
    [spec] = plan.plants
    robot_type = dataclasses.replace(spec.robot_type, idle=behaviour)
    plan.plants[0] = dataclasses.replace(spec, robot_type=robot_type)
    return plan


def _run(plan, until_ns):
    signals = _Signals()
    run = MissionRun(plan, observers=[signals], until_ns=until_ns)
    signals.plant = run.sim.plants["arm"]
    result = run.run()
    return run, result, signals


def test_the_arm3dof_type_declares_a_holding_law(plan_text, hold_task):
    plan = plan_text(hold_task % "" + IDLE_MISSION)
    assert plan.plants[0].robot_type.idle is IdleBehaviour.HOLD


@pytest.mark.parametrize("behaviour", [IdleBehaviour.HOLD, IdleBehaviour.BRAKES])
def test_the_arm_does_not_fall_before_its_first_task(plan_text, hold_task, behaviour):
    plan = _with_idle(plan_text(hold_task % "" + IDLE_MISSION), behaviour)
    run, _, _ = _run(plan, 400_000_000)  # 0.4 s, before Hold starts
    assert np.max(np.abs(run.sim.plants["arm"].qpos)) < 1e-3


def test_without_a_holding_behaviour_the_arm_falls(plan_text, hold_task):
    plan = _with_idle(plan_text(hold_task % "" + IDLE_MISSION), IdleBehaviour.FREE)
    run, _, _ = _run(plan, 400_000_000)
    assert np.max(np.abs(run.sim.plants["arm"].qpos)) > 0.1


def test_idle_and_driven_are_signals_of_the_trace(plan_text, hold_task):
    plan = plan_text(hold_task % "" + IDLE_MISSION)
    run, result, observer = _run(plan, 2_000_000_000)
    signals = observer.signals
    assert result.status == "done"
    [hold] = result.robot_tasks
    names = [(name, value) for _, name, value in signals]
    assert names == [("arm.idle", "hold"), ("arm.driven", True), ("arm.idle", "hold")]
    assert signals[0][0] == 0
    assert hold.start_ns < signals[1][0] <= hold.start_ns + 2_000_000  # its first command
    assert signals[2][0] == hold.end_ns
    # held where Hold left it during the last 0.5 s
    left = observer.idle_at[-1]
    assert np.max(np.abs(run.sim.plants["arm"].qpos - left)) < 2e-3


def test_a_measurement_precondition_at_rest_holds_after_idling(plan_text, hold_task):
    clause = "    precondition measure at_rest(tol = 0.05) within 1 s;"
    plan = plan_text(hold_task % clause + IDLE_MISSION)
    _, result, _ = _run(plan, 2_000_000_000)
    assert result.status == "done", result.reason
    assert [r.outcome for r in result.robot_tasks] == ["good_end"]
