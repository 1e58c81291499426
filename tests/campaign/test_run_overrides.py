"""``orccad run --set`` and ``--timing``: typed overrides of a robot type's parameters, sensor
noise and Module-Task timing, validated against what the mission declares."""

from __future__ import annotations

import json

import pytest

from orccad_app.diagnostics import OrccadError
from orccad_app.mission.overrides import (NoiseOverride, ParamOverride, PlanOverrides,
                                          TimingField, parse_set, parse_timing)

from .conftest import AUV, ROOT, orccad

PID = str(ROOT / "missions" / "arm_pid.orc")


def test_arguments_parse_to_typed_overrides_and_back():
    assert parse_set("auv.cb_height_m=0.02") == ParamOverride("auv", "cb_height_m", 0.02)
    assert parse_set("auv.depth.noise_std=0.05") == NoiseOverride("auv", "depth", 0.05)
    timing = parse_timing("Survey.pilot.wcet_ms=2.5")
    assert (timing.field, timing.value_ns) == (TimingField.WCET, 2_500_000)
    overrides = PlanOverrides.from_arguments(["auv.mass_kg=97", "auv.depth.noise_std=0.1"],
                                             ["Survey.pilot.period_ms=40"])
    assert overrides.arguments() == ["--set", "auv.mass_kg=97", "--set",
                                     "auv.depth.noise_std=0.1", "--timing",
                                     "Survey.pilot.period_ms=40.0"]
    for bad in ("auv=1", "auv.x=abc", "auv.x=nan", "auv.depth.noise_std=-1"):
        with pytest.raises(OrccadError):
            parse_set(bad)
    for bad in ("Survey.pilot.wcet=2", "Survey.pilot.period_ms=0", "S.m.wcet_ms=-1"):
        with pytest.raises(OrccadError):
            parse_timing(bad)


@pytest.mark.parametrize("option, message", [
    (["--set", "auv.cb_height_m=0.5"], "must be <= 0.15"),
    (["--set", "auv.cbh=0.1"], "declares no parameter 'cbh'"),
    (["--set", "arm.x=1"], "no robot 'arm'"),
    (["--set", "auv.sonar.noise_std=0.1"], "no sensor port 'sonar'"),
    (["--timing", "Survey.pilote.wcet_ms=2"], "has no module 'pilote'"),
    (["--timing", "Foo.pilot.wcet_ms=2"], "runs no Robot-Task 'Foo'"),
    (["--timing", "Survey.pilot.bcet_ms=3"], "exceeds its WCET"),
    (["--timing", "Survey.pilot.jitter_ms=3"], "FIELD period_ms, wcet_ms or bcet_ms")])
def test_bad_overrides_exit_2_with_a_reason(option, message):
    result = orccad("run", AUV, "--until", "5", *option)
    assert result.returncode == 2 and message in result.stderr
    assert "Traceback" not in result.stderr


def test_a_heavier_vehicle_cannot_get_its_gps_fix():
    """mass_kg = 110 outweighs the buoyancy (96 kg nominal): the vehicle sinks at the launch
    and StationKeep's GPS fix precondition times out."""
    result = orccad("run", AUV, "--set", "auv.mass_kg=110", "--json")
    assert result.returncode == 1
    assert json.loads(result.stdout)["reason"] == "gps_fix_timeout"


def test_timing_overrides_reach_the_module_tasks():
    result = orccad("run", PID, "--timing", "TrackPID.ctrl.period_ms=2",
                    "--timing", "TrackPID.ctrl.wcet_ms=0.5", "--json")
    data = json.loads(result.stdout)
    ctrl = data["modules"]["TrackPID.ctrl"]
    assert ctrl["period_s"] == 0.002 and ctrl["wcet_s"] == 0.0005 and ctrl["jobs"] == 2000
    nominal = json.loads(orccad("run", PID, "--json").stdout)
    assert nominal["modules"]["TrackPID.ctrl"]["period_s"] == 0.001  # the source untouched
