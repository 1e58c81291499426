"""The AUV's guidance, autopilot and observers as module instances (orccad_auv.control)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from orccad_app.control import ModuleContext
from orccad_app.diagnostics import OrccadError
from orccad_app.plugin_host import PluginHost
from orccad_auv import AUV
from orccad_auv.control import FAR_M, allocate

HOST = PluginHost.load()
CONTEXT = ModuleContext(robot=AUV, robot_name="auv")


def _module(kind: str, **params):
    instance = HOST.module_kind(kind).create(params, CONTEXT)
    instance.init()
    return instance


def _guide(module, x=0.0, y=0.0, depth=0.0, yaw=0.0, t=0.0):
    out = module.compute(t, {"position": np.array([x, y, depth]),
                             "attitude": np.array([0.0, 0.0, yaw])})
    return out["setpoint"], float(out["goal_error"][0])


def test_allocation_gives_the_demanded_forces_and_moments():
    forces = allocate(surge=10.0, heave=6.0, pitch=3.0, sway=1.0, yaw=-2.4)
    arm = 0.6
    assert forces[0] == 10.0
    assert forces[1] + forces[2] == pytest.approx(6.0)
    assert -arm * forces[1] + arm * forces[2] == pytest.approx(3.0)  # r x F about y
    assert forces[3] + forces[4] == pytest.approx(1.0)
    assert arm * forces[3] - arm * forces[4] == pytest.approx(-2.4)
    assert allocate(500.0, 0, 0, 0, 0)[0] == 60.0  # clamped to the thruster's limit


def test_depth_guidance_holds_the_first_heading():
    guide = _module("depth_guidance", depth=15.0)
    setpoint, error = _guide(guide, depth=2.0, yaw=0.7)
    assert setpoint.tolist() == pytest.approx([15.0, 0.7, 0.0, 0.0]) and error == 13.0
    setpoint, _ = _guide(guide, depth=5.0, yaw=0.1, t=0.1)
    assert setpoint[1] == pytest.approx(0.7)


def test_los_guidance_corrects_the_cross_track_error():
    guide = _module("los_guidance", x=100.0, y=0.0, depth=10.0, lookahead=10.0)
    _guide(guide, 0.0, 0.0, 10.0)  # the leg starts here
    setpoint, error = _guide(guide, 50.0, 10.0, 10.0, t=0.1)  # 10 m left of the leg
    assert setpoint[1] == pytest.approx(-math.atan(1.0))
    assert error == pytest.approx(math.hypot(50.0, 10.0))  # the last waypoint: its distance


def test_lawnmower_lanes_and_resume_from_the_nearest_point():
    kind = HOST.module_kind("lawnmower_guidance")
    points = kind.waypoints({"area": [10.0, 0.0, 50.0, 20.0], "spacing": 10.0})
    assert points == [(10, 0), (50, 0), (50, 10), (10, 10), (10, 20), (50, 20)]
    guide = _module("lawnmower_guidance", area=[10.0, 0.0, 50.0, 20.0], depth=8.0)
    setpoint, error = _guide(guide, 12.0, 9.0, 8.0)  # resumes at (10, 10), then (10, 20)
    assert guide.index == 4 and error == FAR_M
    assert setpoint[1] == pytest.approx(math.pi / 2, abs=0.4)  # heading +y
    with pytest.raises(OrccadError, match="x1 > x0"):
        _module("lawnmower_guidance", area=[10.0, 0.0, 5.0, 20.0])


def test_station_guidance_asks_for_body_velocities():
    guide = _module("station_guidance", x=0.0, y=10.0, depth=0.0, gain=0.2, max_speed=0.5)
    setpoint, error = _guide(guide, 0.0, 0.0, 0.0, yaw=math.pi / 2)  # facing +y
    assert setpoint[2:] == pytest.approx([0.5, 0.0], abs=1e-9) and error == 10.0


def test_autopilot_pushes_down_when_too_shallow_and_turns_towards_the_heading():
    pilot = _module("auv_autopilot")
    out = pilot.compute(0.0, {"setpoint": np.array([10.0, 0.5, 1.0, 0.0]),
                              "depth": np.array(5.0), "attitude": np.zeros(3),
                              "velocity": np.zeros(6)})
    tau = out["tau"]
    assert tau[1] + tau[2] < 0  # heave down
    assert 0.6 * (tau[3] - tau[4]) > 0  # yaw moment towards +0.5 rad
    assert tau[0] > 0  # surge


@pytest.mark.parametrize("kind, port, value, fires", [
    ("battery_low", "battery", 19.0, True), ("battery_low", "battery", 21.0, False),
    ("leak", "leak", 1.0, True), ("leak", "leak", 0.0, False),
    ("depth_limit", "depth", 30.5, True), ("depth_limit", "depth", 29.0, False),
    ("altitude_low", "altitude", 4.0, True), ("altitude_low", "altitude", 6.0, False),
    ("at_waypoint", "goal_error", np.array([1.0]), True),
    ("at_waypoint", "goal_error", np.array([FAR_M]), False),
])
def test_observers_fire_on_their_condition(kind, port, value, fires):
    observer = _module(kind)
    out = observer.compute(0.0, {port: np.asarray(value)})
    assert out.get("event", False) is fires
    assert observer.compute(0.1, {}) == {}  # no value yet: nothing


def test_gps_fix_needs_the_fix_held_for_the_acquisition_time():
    observer = _module("gps_fix", acquire=2.0)
    assert "event" not in observer.compute(0.0, {"gps": np.array(1.0)})
    assert "event" not in observer.compute(1.0, {"gps": np.array(0.0)})  # lost: restart
    assert "event" not in observer.compute(2.0, {"gps": np.array(1.0)})
    assert observer.compute(4.0, {"gps": np.array(1.0)})["event"] is True
