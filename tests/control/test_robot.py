"""Robot types read from MJCF, and the plant binding with the actuator constraint."""

import numpy as np
import pytest

from orccad_app.control.errors import ControlError
from orccad_app.control.physics import RobotPhysics
from orccad_app.control.robot import RobotType

PENDULUM = """
<mujoco>
  <worldbody>
    <body name="link">
      <joint name="hinge" type="hinge" axis="0 1 0" range="-1 1"/>
      <inertial pos="0 0 -0.5" mass="1" diaginertia="0.01 0.01 0.01"/>
    </body>
  </worldbody>
  <actuator>{actuator}</actuator>
  <sensor>{sensors}</sensor>
</mujoco>
"""
MOTOR = '<motor name="m" joint="hinge" ctrlrange="-5 5"/>'
SENSORS = '<jointpos name="p" joint="hinge"/><jointvel name="v" joint="hinge"/>'


def write(tmp_path, actuator=MOTOR, sensors=SENSORS):
    path = tmp_path / "pendulum.xml"
    path.write_text(PENDULUM.format(actuator=actuator, sensors=sensors))
    return path


def test_arm_ports_limits_and_resources(arm):
    assert arm.name == "arm3dof" and arm.dof == 3
    assert arm.resources == ("j1", "j2", "j3")
    assert [(p.name, p.spec.direction, p.spec.type, p.dim) for p in arm.ports] == [
        ("q", "out", "vector", 3), ("qdot", "out", "vector", 3), ("tau", "in", "vector", 3)]
    low, high = arm.torque_limits
    assert high.tolist() == [80.0, 120.0, 60.0] and low.tolist() == [-80.0, -120.0, -60.0]
    assert arm.actuator_constraint.alpha.tolist() == [150.0, 200.0, 100.0]
    assert arm.joint_limits[1].tolist() == [2.9, 1.6, 2.5]
    assert arm.end_effector == "end_effector"
    assert arm.default_timing.period_ns == 1_000_000


def test_unknown_port_names_close_matches(arm):
    with pytest.raises(ControlError, match="no port 'qdt' .*did you mean 'qdot'"):
        arm.port("qdt")


def test_from_mjcf_reads_a_minimal_robot(tmp_path):
    robot = RobotType.from_mjcf("pendulum", write(tmp_path), "a pendulum")
    assert robot.dof == 1 and robot.torque_limits[1].tolist() == [5.0]
    assert robot.end_effector is None and robot.sensors[0].mj_names == ("p",)


@pytest.mark.parametrize("actuator, sensors, fragment", [
    ("", SENSORS, "needs one motor with a ctrlrange per joint, found 0"),
    ('<motor joint="hinge" gear="10" ctrlrange="-5 5"/>', SENSORS, "gear 1"),
    (MOTOR, '<jointpos joint="hinge"/>', "'qdot' needs one <jointvel> sensor per joint"),
])
def test_from_mjcf_explains_what_is_missing(tmp_path, actuator, sensors, fragment):
    with pytest.raises(ControlError, match=fragment):
        RobotType.from_mjcf("pendulum", write(tmp_path, actuator, sensors))


def test_from_mjcf_reports_a_missing_file(tmp_path):
    with pytest.raises(ControlError, match="MJCF file not found"):
        RobotType.from_mjcf("ghost", tmp_path / "nowhere.xml")


def test_physics_reads_sensors_and_holds_the_command(arm):
    physics = RobotPhysics(arm)
    physics.set_state([0.1, 0.2, 0.3], [0.0, 0.5, 0.0])
    np.testing.assert_allclose(physics.read("q"), [0.1, 0.2, 0.3])
    np.testing.assert_allclose(physics.read("qdot"), [0.0, 0.5, 0.0])
    physics.write("tau", [1.0, 500.0, -2.0])
    physics.step(3)
    assert physics.time == pytest.approx(0.003)
    np.testing.assert_allclose(physics.data.ctrl, physics.applied_torque())
    assert physics.applied_torque()[1] <= 120.0
    with pytest.raises(ControlError):
        physics.write("q", [0.0, 0.0, 0.0])


def test_physics_applies_the_torque_speed_line(arm):
    physics = RobotPhysics(arm)
    physics.set_state([0.0, 0.0, 0.0], [0.0, 4.0, 0.0])
    physics.write("tau", [0.0, 200.0, 0.0])
    # shoulder: alpha - beta * qdot = 200 - 30 * 4 = 80 N·m < tau_max = 120 N·m
    assert physics.applied_torque()[1] == pytest.approx(80.0)
