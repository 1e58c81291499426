"""The AUV plant: buoyancy, restoring moment, battery, sensors and faults (orccad_auv.physics)."""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest

from orccad_app.diagnostics import OrccadError
from orccad_app.executive.plant import MujocoPlant
from orccad_auv import AUV
from orccad_auv.physics import G_MPS2, euler_zyx


def _plant(depth_m: float = 20.0, roll_rad: float = 0.0, **params) -> MujocoPlant:
    robot = AUV.configure(params) if params else AUV
    plant = MujocoPlant("auv", path=str(robot.mjcf_path), extension=robot.plant_extension())
    plant.data.qpos[2] = -depth_m
    plant.data.qpos[3:7] = [math.cos(roll_rad / 2), math.sin(roll_rad / 2), 0.0, 0.0]
    mujoco.mj_forward(plant.model, plant.data)
    return plant


def _run(plant: MujocoPlant, seconds: float) -> None:
    plant.advance_to(plant.time_ns + int(seconds * 1e9))


def test_slightly_positive_vehicle_rises_at_the_terminal_velocity():
    """(rho V - m) g = rho C_blunt A |v| v (MuJoCo's ellipsoid blunt drag; A = pi a b, the
    hull's projected area seen from below; the slender term vanishes on a principal axis)."""
    plant = _plant()
    p = plant.extension.params
    mass = plant.model.body_mass[1]
    a, b = plant.model.geom_size[1][:2]
    blunt = plant.model.geom_fluid[1][1]
    net_n = (p["water_density"] * p["volume_m3"] - mass) * G_MPS2
    assert net_n > 0  # slightly positive: +0.6 kg
    terminal = math.sqrt(net_n / (p["water_density"] * blunt * math.pi * a * b))
    _run(plant, 20.0)
    assert plant.qvel[2] == pytest.approx(terminal, rel=0.01)  # 0.274 m/s
    depth0 = plant.extension.true_value("depth")
    _run(plant, 10.0)
    rise = (depth0 - plant.extension.true_value("depth")) / 10.0
    assert rise == pytest.approx(terminal, rel=0.01)


def test_floats_at_the_surface_with_the_weight_balancing_the_buoyancy():
    plant = _plant(depth_m=2.0)
    _run(plant, 60.0)
    ext = plant.extension
    assert abs(plant.qvel[2]) < 0.01
    assert ext.buoyancy_n() == pytest.approx(plant.model.body_mass[1] * G_MPS2, rel=1e-3)
    assert 0.0 < float(ext.true_value("depth")) < 0.2  # slightly emerged
    assert float(ext.read("gps")) == 1.0


def test_rights_itself_from_a_roll():
    """The centre of buoyancy 5 cm above the CG: restoring moment B h sin(roll)."""
    plant = _plant(roll_rad=0.6)
    roll = []
    for _ in range(200):
        _run(plant, 0.05)
        roll.append(plant.extension.true_value("attitude")[0])
    roll = np.abs(roll)
    assert roll[:20].max() > 0.3  # it started rolled
    assert roll[-40:].max() < 0.05  # and is upright after 8 s


def test_no_righting_moment_without_a_metacentric_height():
    plant = _plant(roll_rad=0.6, cb_height_m=0.0)
    _run(plant, 5.0)
    assert abs(plant.extension.true_value("attitude")[0]) > 0.4


def test_battery_integrates_hotel_load_and_thruster_power():
    plant = _plant(battery_wh=1.0)
    ext = plant.extension
    _run(plant, 36.0)  # hotel 20 W for 36 s = 720 J of 3600 J
    assert float(ext.read("battery")) == pytest.approx(80.0, abs=0.1)
    plant.data.ctrl[0] = 16.0  # 0.5 W/N^1.5 x 16^1.5 = 32 W more
    _run(plant, 10.0)
    assert float(ext.read("battery")) == pytest.approx(80.0 - 520.0 / 36.0, abs=0.1)


def test_sensors_read_the_state_in_their_frames():
    plant = _plant(depth_m=10.0)
    ext = plant.extension
    assert float(ext.read("depth")) == pytest.approx(10.0)
    assert float(ext.read("altitude")) == pytest.approx(30.0)  # seabed at 40 m
    assert ext.read("position") == pytest.approx([0.0, 0.0, 10.0])
    assert float(ext.read("gps")) == 0.0 and float(ext.read("leak")) == 0.0
    plant.data.qpos[3:7] = [math.cos(0.25), 0.0, 0.0, math.sin(0.25)]  # yaw 0.5 rad
    plant.data.qvel[:3] = [1.0, 0.0, 0.0]
    mujoco.mj_forward(plant.model, plant.data)
    assert ext.read("attitude") == pytest.approx([0.0, 0.0, 0.5])
    u, v = ext.read("velocity")[:2]
    assert (u, v) == pytest.approx((math.cos(0.5), -math.sin(0.5)))


def test_euler_angles_of_a_pitch():
    q = [math.cos(0.1), 0.0, math.sin(0.1), 0.0]
    assert euler_zyx(np.array(q)) == pytest.approx([0.0, 0.2, 0.0])


def test_faults_bias_freeze_and_set_sensors():
    plant = _plant(depth_m=10.0)
    ext = plant.extension
    plant.inject("depth_bias", 2.5)
    assert float(ext.read("depth")) == pytest.approx(12.5)
    plant.inject("altitude_stuck", 1)
    _run(plant, 5.0)
    assert float(ext.read("altitude")) == pytest.approx(30.0)
    plant.inject("altitude_stuck", 0)
    assert float(ext.read("altitude")) > 30.5
    plant.inject("battery", 5.0)
    assert float(ext.read("battery")) == pytest.approx(5.0)
    plant.inject("leak", True)
    assert float(ext.read("leak")) == 1.0
    with pytest.raises(OrccadError, match="no fault 'flood'"):
        plant.inject("flood", 1)


def test_a_leak_makes_the_vehicle_heavy():
    plant = _plant(depth_m=20.0, leak_rate_kg_s=0.1)
    plant.inject("leak", 1)
    _run(plant, 30.0)  # 3 kg of water: 2.4 kg negative
    assert plant.qvel[2] < -0.3


def test_thrust_fault_scales_every_thruster_and_gps_can_be_denied():
    plant = _plant(depth_m=0.1)
    plant.inject("thrust", 0.0)
    plant.data.ctrl[:] = [60.0, 0, 0, 0, 0]
    _run(plant, 2.0)
    assert abs(plant.qvel[0]) < 1e-6
    plant.inject("gps_denied", 1)
    assert float(plant.extension.read("gps")) == 0.0
