"""Resolving components by name, with nested trajectories, and building contexts."""

import pytest

from orccad_app.control.errors import DimensionMismatch
from orccad_app.control.spec import module_context, resolve
from orccad_app.control.trajectories import Cosine
from orccad_app.diagnostics import OrccadError


def test_resolve_builds_nested_trajectories(host, arm):
    spec = resolve(host, "task function", ("joint_tracking", {
        "trajectory": {"kind": "cosine", "q0": [0.5, 0.5, 0.5], "omega": 2.0}}))
    assert isinstance(spec.params["trajectory"], Cosine)
    task = spec.build(arm)
    assert task.trajectory.omega == 2.0 and task is not spec.build(arm)


def test_unknown_names_list_close_matches(host):
    with pytest.raises(OrccadError, match="unknown trajectory 'cosin' .*did you mean 'cosine'"):
        resolve(host, "task function", ("joint_tracking", {"trajectory": "cosin"}))
    with pytest.raises(OrccadError, match="unknown control law 'pd'"):
        resolve(host, "control law", ("pd", {}))


def test_module_context_runs_the_coherence_checks(host):
    with pytest.raises(DimensionMismatch, match="trajectory 'cosine' has 2 components"):
        module_context(host, "arm3dof", ("joint_tracking", {
            "trajectory": ("cosine", {"q0": [0.5, 0.5]})}), ("pid", {}))
    with pytest.raises(OrccadError, match="pid: kp must be > 0, got -1.0"):
        module_context(host, "arm3dof", ("joint_tracking", {
            "trajectory": ("cosine", {"q0": [0.5] * 3})}), ("pid", {"kp": -1.0}))
    with pytest.raises(OrccadError, match="unknown robot type 'arm2dof'"):
        module_context(host, "arm2dof")


def test_module_context_carries_the_task(cosine_context):
    context = cosine_context()
    assert context.robot.name == "arm3dof" and context.law.name == "pid"
    assert context.task_function.name == "joint_tracking" and context.duration_s == 4.0
