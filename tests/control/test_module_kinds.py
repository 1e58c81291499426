"""The ``trajectory`` and ``control_law`` module kinds, driven like the executive does."""

import math

import numpy as np
import pytest

from orccad_app.control.errors import ControlError, InvalidParameter
from orccad_app.control.module import ModuleContext
from orccad_app.control.module_kinds import ControlLawModule, TrajectoryModule
from orccad_app.control.spec import module_context


def test_trajectory_module_samples_the_cosine_from_its_first_job(cosine_context):
    traj = TrajectoryModule().create({}, cosine_context())
    assert [(p.name, p.direction, p.dim) for p in traj.ports if p.direction == "out"] == [
        ("qd", "out", 3), ("qd_dot", "out", 3), ("qd_ddot", "out", 3)]
    traj.init()
    first = traj.compute(5.0, {})
    np.testing.assert_allclose(first["qd"], [1.0, 1.0, 1.0])
    later = traj.compute(5.5, {})
    np.testing.assert_allclose(later["qd"], 0.5 * (1 + math.cos(math.pi * 0.5)) * np.ones(3))
    np.testing.assert_allclose(later["qd_dot"], -0.5 * math.pi * np.ones(3))


def test_trajectory_module_takes_a_missing_start_from_q(host):
    context = module_context(host, "arm3dof", ("joint_tracking", {
        "trajectory": ("min_jerk", {"goal": [0.0, 0.0, 0.0], "duration": 1.0})}))
    traj = TrajectoryModule().create({}, context)
    traj.init()
    assert traj.compute(0.0, {}) == {}
    out = traj.compute(0.002, {"q": [0.3, 0.2, 0.1]})
    np.testing.assert_allclose(out["qd"], [0.3, 0.2, 0.1])
    np.testing.assert_allclose(traj.compute(1.002, {"q": [9.0, 9.0, 9.0]})["qd"], 0.0, atol=1e-12)


def test_control_law_module_ports_and_outputs(cosine_context):
    ctrl = ControlLawModule().create({}, cosine_context())
    ports = {p.name: p for p in ctrl.ports}
    assert ports["qd"].required and not ports["qdot"].required and ports["tau"].dim == 3
    assert ports["saturated"].type == "bool"
    ctrl.init()
    out = ctrl.compute(0.0, {"qd": [1.0, 1.0, 1.0], "qd_dot": [0.0] * 3, "qd_ddot": [0.0] * 3,
                             "q": [0.99, 1.0, 1.01], "qdot": [0.0] * 3})
    np.testing.assert_allclose(out["tau"], [4.0, 0.0, -4.0])
    np.testing.assert_allclose(out["e"], [-0.01, 0.0, 0.01])
    assert out["saturated"] is False


def test_control_law_module_writes_nothing_without_its_required_inputs(cosine_context):
    ctrl = ControlLawModule().create({}, cosine_context())
    ctrl.init()
    assert ctrl.compute(0.0, {"q": [1.0, 1.0, 1.0]}) == {}
    assert ctrl.compute(0.0, {"qd": [1.0, 1.0, 1.0], "q": None}) == {}


def test_unconnected_velocities_are_estimated_by_differences(cosine_context):
    ctrl = ControlLawModule().create({"ki": 0.0}, cosine_context())
    ctrl.init()
    ctrl.compute(0.0, {"qd": [1.0, 1.0, 1.0], "q": [1.0, 1.0, 1.0]})
    out = ctrl.compute(0.001, {"qd": [1.0, 1.0, 1.0], "q": [1.001, 1.0, 1.0]})
    # qdot = 1 rad/s on joint 1 -> kv * 1 + kp * 0.001
    np.testing.assert_allclose(out["tau"], [-(40.0 + 0.4), 0.0, 0.0])


def test_adjust_retunes_the_law_between_jobs(cosine_context):
    ctrl = ControlLawModule().create({}, cosine_context())
    ctrl.init()
    inputs = {"qd": [1.0] * 3, "qd_dot": [0.0] * 3, "q": [1.01, 1.0, 1.0], "qdot": [0.0] * 3}
    before = ctrl.compute(0.0, inputs)["tau"][0]
    ctrl.set_param("kp", 200.0)
    assert ctrl.params["kp"] == 200.0
    assert ctrl.compute(0.0, inputs)["tau"][0] == pytest.approx(before / 2)
    with pytest.raises(InvalidParameter, match="kp must be > 0"):
        ctrl.set_param("kp", 0.0)


def test_module_parameters_override_the_law(cosine_context):
    ctrl = ControlLawModule().create({"kp": 100.0}, cosine_context())
    assert ctrl.params["kp"] == 100.0 and ctrl.params["ki"] == 10.0
    with pytest.raises(InvalidParameter, match="pid has no parameter 'kq'"):
        ControlLawModule().create({"kq": 1.0}, cosine_context())


def test_modules_need_the_robot_task_context():
    with pytest.raises(ControlError, match="control_law needs the Robot-Task's law"):
        ControlLawModule().create({}, ModuleContext())
    with pytest.raises(ControlError, match="trajectory needs a robot"):
        TrajectoryModule().create({}, ModuleContext())


def test_cartesian_tasks_name_the_reference_xd(host):
    context = module_context(host, "arm3dof", ("cartesian_tracking", {
        "trajectory": ("constant", {"value": [0.5, 0.0, 0.8]})}), ("computed_torque", {}))
    names = [p.name for p in TrajectoryModule().create({}, context).ports]
    assert names[:3] == ["xd", "xd_dot", "xd_ddot"]
    ctrl = ControlLawModule().create({}, context)
    assert {"xd", "xd_dot", "xd_ddot", "q", "qdot", "tau", "e"} <= {p.name for p in ctrl.ports}
