"""missions/auv_survey.orc end to end in the executive: every recovery path, faults injected.

Each run asserts the mission's status and reason, the Robot-Tasks that ran and the vehicle's
final state (at the surface, never below the 30 m limit)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from orccad_app.cli import main
from orccad_app.diagnostics import OrccadError
from orccad_app.mission.plan import plan_mission
from orccad_app.mission.injection import PlantFault, parse_injection
from orccad_app.mission.run import MissionRun
from orccad_app.pipeline import load, select_mission

ROOT = Path(__file__).resolve().parents[2]
MISSION = ROOT / "missions" / "auv_survey.orc"
UNTIL_NS = 900_000_000_000


@pytest.fixture(scope="module")
def plan():
    source = load(str(MISSION))
    return plan_mission(source, select_mission(source, None))


def _run(plan, *injections: str):
    run = MissionRun(plan, until_ns=UNTIL_NS,
                     injections=[parse_injection(text) for text in injections])
    result = run.run()
    return result, run.sim.plants["auv"].extension


def _tasks(result) -> list[tuple[str, str]]:
    return [(r.name, r.outcome) for r in result.robot_tasks]


def _surfaced(vehicle) -> None:
    assert float(vehicle.true_value("depth")) < 0.5
    assert vehicle.max_depth_m < 30.0  # never below the maximum depth


def test_nominal_survey_is_done_at_the_surface(plan):
    result, vehicle = _run(plan)
    assert (result.status, result.reason) == ("done", None)
    assert _tasks(result) == [("StationKeep", "good_end"), ("Dive", "good_end"),
                              ("GoTo", "good_end"), ("Survey", "good_end"),
                              ("Surface", "good_end"), ("StationKeep", "good_end")]
    assert 150.0 < result.sim_time_ns / 1e9 < 400.0
    _surfaced(vehicle)
    assert vehicle.max_depth_m == pytest.approx(15.0, abs=1.0)
    x, y = vehicle.true_value("position")[:2]
    assert abs(x - 50.0) < 3.0 and abs(y - 20.0) < 3.0  # recovered at the survey's end
    assert 50.0 < vehicle.battery_percent() < 100.0


def test_a_leak_mid_survey_aborts_and_surfaces_at_once(plan):
    result, vehicle = _run(plan, "auv.leak=1@120")
    assert (result.status, result.reason) == ("aborted", "Leak")
    assert _tasks(result)[-2:] == [("Survey", "Leak"), ("Surface", "good_end")]
    [record] = result.exceptions
    assert (record.name, record.type.number, record.time_ns) == ("Leak", 3, pytest.approx(120e9, abs=2e8))
    _surfaced(vehicle)


def test_low_battery_ends_the_survey_surfaces_and_fails(plan):
    result, vehicle = _run(plan, "auv.battery=15%@120")
    assert (result.status, result.reason) == ("failed", "BatteryLow")
    assert _tasks(result)[-3:] == [("Survey", "BatteryLow"), ("Surface", "good_end"),
                                   ("StationKeep", "BatteryLow")]
    _surfaced(vehicle)


def test_too_close_to_the_seabed_climbs_and_resumes(plan):
    result, vehicle = _run(plan, "auv.altitude_bias=-22@120")  # reads 3 m above the seabed
    assert result.status == "done"
    assert _tasks(result)[3:7] == [("Survey", "AltitudeLow"), ("Dive", "good_end"),
                                   ("Survey", "good_end"), ("Surface", "good_end")]
    assert ("AltitudeLow", 2) in [(e.name, e.type.number) for e in result.exceptions]
    _surfaced(vehicle)


def test_depth_limit_is_fatal_and_surfaces(plan):
    result, vehicle = _run(plan, "Survey.DepthLimit@130")  # the observer's event as a signal
    assert (result.status, result.reason) == ("aborted", "DepthLimit")
    assert _tasks(result)[-1] == ("Surface", "good_end")
    _surfaced(vehicle)


def test_no_gps_fix_at_launch_fails_on_the_watchdog(plan):
    result, vehicle = _run(plan, "auv.gps_denied=1@0")
    assert (result.status, result.reason) == ("failed", "gps_fix_timeout")
    assert result.sim_time_ns == 30_000_000_000
    _surfaced(vehicle)


def test_unknown_faults_and_robots_are_reported(plan):
    with pytest.raises(OrccadError, match="robot 'auv' has no fault 'flood'"):
        MissionRun(plan, injections=[parse_injection("auv.flood=1@1")])
    with pytest.raises(OrccadError, match="no robot 'sub'"):
        MissionRun(plan, injections=[parse_injection("sub.leak=1@1")])


def test_fault_injection_syntax():
    fault = parse_injection("auv.battery=5%@60")
    assert (fault.name, fault.time_ns, fault.value, fault.fault) == (
        "auv.battery", 60_000_000_000, 5, PlantFault("auv", "battery"))
    assert parse_injection("auv.leak = true @ 2.5s").value is True
    assert parse_injection("Stop@2").fault is None
    assert parse_injection("Dive.Leak@2").fault is None  # an observer event: a dot, no fault
    with pytest.raises(OrccadError, match="ROBOT.FAULT=VALUE@SECONDS"):
        parse_injection("auv.battery=low@60")


def test_orccad_run_json_without_until_uses_the_robot_horizon(capsys):
    assert main(["run", str(MISSION), "--json"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert report["status"] == "done"
    assert main(["run", str(MISSION), "--json", "--inject", "auv.leak=1@100"]) == 1
    report = json.loads(capsys.readouterr().out)
    assert (report["status"], report["reason"]) == ("aborted", "Leak")
