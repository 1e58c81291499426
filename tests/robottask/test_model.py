"""Robot-Tasks checked against the plugin registries: every error names the bad value and
points at its clause."""

from __future__ import annotations

import pytest

from orccad_app.diagnostics import OrccadError
from orccad_app.pipeline import load
from orccad_app.tcs.port import PortRef

ARM_PID = open("missions/arm_pid.orc", encoding="utf-8").read()


def error_of(tmp_path, old: str, new: str) -> OrccadError:
    assert old in ARM_PID
    path = tmp_path / "m.orc"
    path.write_text(ARM_PID.replace(old, new), encoding="utf-8")
    with pytest.raises(OrccadError) as caught:
        load(path)
    return caught.value


def line_of(text: str) -> int:
    return next(i for i, line in enumerate(ARM_PID.splitlines(), 1) if text in line)


@pytest.mark.parametrize("old,new,message,anchor", [
    ("law pid(", "law pdi(", "unknown control law 'pdi'", "law "),
    ("ki = 10.0", "ki = -1.0", "ki must be >= 0, got -1.0", "law "),
    ("joint_tracking(", "joint_trackin(", "unknown task function 'joint_trackin'", "task_function"),
    ("module ctrl : control_law", "module ctrl : control_lw", "control_lw", "module ctrl"),
    ("connect arm.q       -> ctrl.q ", "connect arm.q       -> ctrl.qq ", "no port 'qq'", "arm.q       -> ctrl.q "),
    ("connect traj.qd     -> ctrl.qd ", "connect traj.qd     -> ctrl.q ", "already fed", "arm.q       -> ctrl.q "),
    ("connect ctrl.tau    -> arm.tau ", "connect arm.tau -> ctrl.tau ", "is an input port", "ctrl.tau    -> arm.tau"),
    ("tracking_error(max = 0.2)", "tracking_error(maxx = 0.2)", "no parameter 'maxx'", "TrackingLost"),
    ("from jl : fatal", "from traj : fatal", "is not an observer", "JointLimit"),
    ("adjust ctrl.kp = 200.0", "adjust ctrl.kp = -2.0", "kp", "Saturated"),
    ("q0: vector = [0.5, 0.5, 0.5]", "q0: vector = [0.5, 0.5]", "dim e = 3", "task_function"),
])
def test_incoherent_task_is_rejected_at_its_clause(tmp_path, old, new, message, anchor):
    error = error_of(tmp_path, old, new)
    assert message in error.message
    assert error.location.line == line_of(anchor)


def test_unconnected_required_input_is_named(tmp_path):
    error = error_of(tmp_path, "    connect arm.q       -> ctrl.q      : asyn/asyn;\n", "")
    assert "input ctrl.q" in error.message and "not connected" in error.message


def test_vector_dimensions_must_agree(tmp_path):
    from orccad_app.robottask.wiring import _check_pair
    from orccad_app.control.module import PortSpec
    with pytest.raises(OrccadError, match="a vector of 3 cannot feed a vector of 2"):
        _check_pair(PortSpec("a", "out", "vector", 3), PortSpec("b", "in", "vector", 2), "x", None)


def test_implicit_observers_are_wired_and_timed_by_their_kind():
    from orccad_app.robottask.model import check_tasks
    source = load("missions/arm_pid.orc")
    instance = check_tasks(source.program, source.host).defaults["TrackPID"]
    tracking = instance.modules["tracking_error"]
    assert tracking.implicit and tracking.timing == tracking.kind.default_timing
    wired = {str(c) for c in instance.connections if c.implicit}
    assert "ctrl.e -> tracking_error.e" in wired and "arm.q -> tracking_error.q" in wired
    assert instance.events["TrackingLost"] == PortRef("tracking_error", "event")
    assert instance.adjustments["Saturated"].value == 200.0
    assert instance.modules["ctrl"].priority == 1 and instance.modules["jl"].priority == 3
