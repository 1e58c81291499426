"""Sensor noise and quantization as robot type parameters: declared by the robot plugins through
the public plugin API, set from the mission's robot declaration or ``--set ROBOT.PARAM=V``,
validated (exit 2 with a location or the ``--set`` argument), seeded by the run's seed, and
varied by campaigns."""

from __future__ import annotations

import csv
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from orccad_app.plugin_api import SensorParam, SensorSetting

ROOT = Path(__file__).resolve().parents[2]

HOLD = """robot arm : arm3dof%s;
robottask Hold() on arm {
    duration 0.02 s;
    task_function joint_tracking(trajectory = constant(value = [0.5, 0.5, 0.5]));
    law pid(kp = 400.0, kv = 40.0);
}
mission M { run Hold(); }
"""


def orccad(*args: str, cwd: Path = ROOT) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "orccad_app.cli", *args], capture_output=True,
                          text=True, cwd=cwd, timeout=600)


def _mission(tmp_path: Path, robot_args: str = "") -> str:
    path = tmp_path / "hold.orc"
    path.write_text(HOLD % robot_args, encoding="utf-8")
    return str(path)


def _q_reads(tmp_path: Path, mission: str, *options: str) -> np.ndarray:
    """The values of ``arm.q`` the control law read, one row per job."""
    trace = tmp_path / "trace.csv"
    result = orccad("run", mission, "--trace", str(trace), *options)
    assert result.returncode == 0, result.stderr
    with trace.open(encoding="utf-8") as stream:
        rows = [json.loads(r["value"]) for r in csv.DictReader(stream)
                if r["event"] == "read" and r["module"] == "Hold.ctrl" and r["port"] == "q"]
    return np.array(rows)


def test_the_robot_plugins_declare_their_sensor_parameters():
    from orccad_arm3dof import ARM3DOF
    from orccad_auv import AUV

    arm = {p.name: p for p in ARM3DOF.sensor_params}
    assert set(arm) == {"noise_std", "qdot_noise_std", "quantization"}
    assert (arm["noise_std"].ports, arm["noise_std"].setting, arm["noise_std"].unit) == \
        (("q",), SensorSetting.NOISE_STD, "[rad]")
    assert (arm["quantization"].setting, arm["qdot_noise_std"].unit) == \
        (SensorSetting.QUANTIZATION, "[rad/s]")
    assert ARM3DOF.sensor_noise() == {"q": 0.0, "qdot": 0.0}  # ideal sensors by default
    noisy = ARM3DOF.configure({"noise_std": 1e-4, "quantization": 1e-5})
    assert noisy.sensor_noise()["q"] == 1e-4 and noisy.sensor_quantization()["q"] == 1e-5
    assert noisy.param_values == {}  # sensor values are kept apart from the type's parameters
    assert {p.name for p in AUV.sensor_params} == {"depth_noise_std", "attitude_noise_std"}
    assert AUV.configure({"depth_noise_std": 0.1}).sensor_noise()["depth"] == 0.1
    assert AUV.sensor_noise()["depth"] == 0.02
    assert {"depth_noise_std", "battery_wh"} <= {p.name for p in AUV.parameters}


def test_a_sensor_parameter_must_name_a_sensor_port():
    from orccad_app.plugin_api import ControlError
    from orccad_arm3dof import ARM3DOF

    bad = SensorParam("tau_noise", ("tau",), SensorSetting.NOISE_STD, 0.0, "[N·m]", "x")
    with pytest.raises(ControlError, match="names no sensor port 'tau'"):
        ARM3DOF.configure({}).__class__(**{**ARM3DOF.__dict__, "sensor_params": (bad,)})


def test_noise_and_quantization_from_the_mission_reach_the_sensors(tmp_path):
    ideal = _q_reads(tmp_path, _mission(tmp_path))
    noisy = _q_reads(tmp_path, _mission(tmp_path, "(noise_std = 1e-3, quantization = 1e-4)"))
    assert ideal.shape == noisy.shape == (20, 3)
    assert np.allclose(noisy / 1e-4, np.round(noisy / 1e-4), atol=1e-6)  # quantized
    deviation = noisy - ideal
    assert 3e-4 < deviation.std() < 3e-3  # ~1e-3 rad of noise (the arm barely moves)


def test_set_overrides_the_mission_and_the_seed_drives_the_noise(tmp_path):
    mission = _mission(tmp_path, "(noise_std = 1e-3)")
    quiet = _q_reads(tmp_path, mission, "--set", "arm.noise_std=0")
    again = _q_reads(tmp_path, mission, "--set", "arm.noise_std=0", "--seed", "5")
    noisy = _q_reads(tmp_path, mission, "--seed", "5")
    same = _q_reads(tmp_path, mission, "--seed", "5")
    other = _q_reads(tmp_path, mission, "--seed", "6")
    assert np.array_equal(quiet, again)  # no noise: the seed does not matter
    assert np.array_equal(noisy, same)  # same seed, same noise, bit for bit
    assert not np.array_equal(noisy, other)
    assert np.abs(noisy - quiet).max() > 1e-4


@pytest.mark.parametrize("robot_args, options, message", [
    ("(noise_sd = 1.0)", (), "arm3dof has no parameter 'noise_sd' (did you mean 'noise_std'"),
    ("(noise_std = -1.0)", (), "noise_std must be >= 0, got -1.0"),
    ('(noise_std = "high")', (), "noise_std must be a number"),
    ("(quantization = 1.0)", (), "quantization must be <= 0.1"),
    ("", ("--set", "arm.noise_sd=1"), "declares no parameter 'noise_sd' (did you mean "
                                       "'noise_std' or 'qdot_noise_std'?) (parameters: "
                                       "noise_std, qdot_noise_std, quantization)"),
    ("", ("--set", "arm.noise_std=-1"), "--set arm.noise_std=-1: arm3dof: noise_std must be >= 0"),
    ("", ("--set", "arm.noise_std=true"), "noise_std must be a number"),
    ("", ("--set", "arm.noise_std=inf"), "'inf' is not a scalar value (a finite number"),
])
def test_bad_sensor_parameters_exit_2_with_a_location(tmp_path, robot_args, options, message):
    mission = _mission(tmp_path, robot_args)
    result = orccad("run", mission, *options)
    assert result.returncode == 2, result.stderr
    assert message in result.stderr and "Traceback" not in result.stderr
    if robot_args:
        assert f"{mission}:1:" in result.stderr  # located at the robot declaration


def test_a_non_finite_parameter_value_is_refused():
    from orccad_app.plugin_api import InvalidParameter
    from orccad_arm3dof import ARM3DOF

    with pytest.raises(InvalidParameter, match="finite"):
        ARM3DOF.configure({"noise_std": float("inf")})


def test_a_campaign_varies_the_arms_noise(tmp_path):
    spec = tmp_path / "noise.campaign.toml"
    spec.write_text('mission = "ArmPID"\nruns = 3\nseed = 4\nuntil_s = 0.3\n'
                    '[params]\n"arm.noise_std" = "U(0.0, 0.01)"\n', encoding="utf-8")
    result = orccad("campaign", "missions/arm_pid.orc", "--spec", str(spec), "--runs", "3",
                    "--workers", "1", "--db", str(tmp_path / "noise.db"), "--json")
    assert result.returncode == 0, result.stderr
    runs = json.loads(result.stdout)["results"]
    drawn = [run["setting"]["values"]["arm.noise_std"] for run in runs]
    assert len(set(drawn)) == 3 and all(0.0 <= v <= 0.01 for v in drawn)
    rms = [run["metrics"]["TrackPID.tracking_error.rms"] for run in runs]
    assert rms.index(max(rms)) == drawn.index(max(drawn))  # the noisiest run tracks worst
    for run in runs:  # each run's replay command carries its noise
        assert any(f"arm.noise_std={value!r}" in arg
                   for value in [run["setting"]["values"]["arm.noise_std"]]
                   for arg in run["setting"]["sets"]), run["setting"]


def test_orccad_plugins_lists_the_sensor_parameters_with_their_range_and_unit():
    listing = json.loads(orccad("plugins", "--json").stdout)
    arm = next(r for r in listing["robot_types"] if r["name"] == "arm3dof")
    noise = next(p for p in arm["params"] if p["name"] == "noise_std")
    assert (noise["type"], noise["default"], noise["minimum"], noise["maximum"]) == \
        ("float", 0.0, 0.0, 0.1)
    assert noise["doc"].endswith("[rad]")
    text = orccad("plugins", "-v").stdout
    assert "param noise_std: float = 0.0  in [0, 0.1]  joint position measurement noise" in text
