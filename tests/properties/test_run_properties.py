"""Every property judged on a real run: ``orccad run`` reports, strict JSON, exit statuses,
and the API campaigns use (PropertyMonitor)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from orccad_app.mission.injection import parse_injection
from orccad_app.mission.plan import plan_mission
from orccad_app.mission.run import MissionRun
from orccad_app.pipeline import load, select_mission
from orccad_app.properties import PropertyKind, PropertyMonitor, Verdict

ROOT = Path(__file__).resolve().parents[2]
PID = (ROOT / "missions" / "arm_pid.orc").read_text(encoding="utf-8")
EXTRA = """
property ArmPID.shoulder_tight: always (arm.q[0] < 0.9);
property ArmPID.reaches_one: eventually[0, 2] (abs(arm.q[1] - 1.0) < 0.05);
property ArmPID.one_end: never (done and failed);
property ArmPID.calm_while_tracking: always (active(TrackPID) -> norm(arm.qdot) < 3.0);
property ArmPID.error_bound: always (abs(arm.e[0]) < 1.0 and abs(arm.e[1]) < 1.0
                                     and abs(arm.e[2]) < 1.0);
"""


def _strict(text: str):
    def refuse(constant):
        raise ValueError(f"not strict JSON: {constant}")
    return json.loads(text, parse_constant=refuse)


def orccad(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "orccad_app.cli", *args],
                          capture_output=True, text=True, cwd=ROOT)


@pytest.fixture(scope="module")
def arm_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("props") / "arm_props.orc"
    path.write_text(PID + EXTRA, encoding="utf-8")
    return path


@pytest.fixture(scope="module")
def arm_report(arm_file):
    result = orccad("run", str(arm_file), "--json")
    return result.returncode, _strict(result.stdout)


def test_a_violated_property_fails_the_run_and_a_satisfied_one_passes(arm_report):
    status, report = arm_report
    assert status == 1 and report["status"] == "done"
    by_name = {p["name"]: p for p in report["properties"]}
    assert list(by_name) == ["tracked_at_good_end", "terminates", "fatal_aborts",
                             "at_rest_at_end", "shoulder_in_range", "tracking_bound",
                             "shoulder_tight",
                             "reaches_one", "one_end", "calm_while_tracking", "error_bound"]
    tight = by_name["shoulder_tight"]
    assert (tight["kind"], tight["verdict"], tight["unit"]) == ("signal", "false", "[rad]")
    # the shoulder follows q0 (1 + cos(pi t)) = 1.0 rad at t = 0: about 0.1 rad over 0.9
    assert -0.15 < tight["robustness"] < -0.05
    inside = by_name["shoulder_in_range"]
    assert inside["verdict"] == "true" and 0.0 < inside["robustness"] < 0.15
    # shoulder_in_range's upper margin is min(1.1 - q) = shoulder_tight's + 0.2 rad; the
    # conjunction takes the smaller of it and the lower margin min(q + 0.1)
    assert inside["robustness"] <= tight["robustness"] + 0.2 + 1e-12
    assert by_name["reaches_one"]["robustness"] == pytest.approx(0.05)  # q(0) = 1.0 exactly
    for name in ("tracked_at_good_end", "terminates", "fatal_aborts", "one_end"):
        assert (by_name[name]["kind"], by_name[name]["verdict"]) == ("ltl", "true")
        assert by_name[name]["robustness"] is None
    # active(TrackPID) holds during the run: the bound decides, finite robustness [rad/s]
    calm = by_name["calm_while_tracking"]
    assert calm["verdict"] == "true" and 0.0 < calm["robustness"] < 3.0
    # arm.e is the control law's task error: its worst component is the report's maximum
    [task] = report["robot_tasks"]
    assert by_name["error_bound"]["robustness"] == pytest.approx(
        1.0 - task["tracking_error"]["max"], abs=1e-12)
    assert 0.0 < by_name["tracking_bound"]["robustness"] < 0.05
    assert by_name["at_rest_at_end"]["samples"] == 4001  # 1 ms samples over 4 s, both ends


def test_the_text_report_names_the_violation(arm_file):
    result = orccad("run", str(arm_file))
    assert result.returncode == 1
    assert "Properties on this run:" in result.stdout
    assert "false     signal shoulder_tight   robustness -0.1" in result.stdout
    assert "property violated on this run: shoulder_tight" in result.stderr


def test_shipped_missions_hold_their_properties_on_a_nominal_run():
    result = orccad("run", "missions/arm_computed_torque.orc", "--json")
    assert result.returncode == 0, result.stderr
    verdicts = {p["name"]: p["verdict"] for p in _strict(result.stdout)["properties"]}
    assert set(verdicts.values()) == {"true"} and "at_rest_at_end" in verdicts


def test_check_proves_ltl_and_leaves_signal_properties_to_runs(arm_file):
    result = orccad("check", str(arm_file))
    assert result.returncode == 0, result.stdout
    assert "signal property shoulder_tight: not proved" in result.stdout
    assert "ok    property one_end" in result.stdout
    assert "left to runs" in result.stdout.splitlines()[-1]


def _run(path: Path, *injections: str, until_s: float = 60.0):
    source = load(path)
    mission = select_mission(source, None)
    plan = plan_mission(source, mission)
    run = MissionRun(plan, seed=0, until_ns=int(until_s * 1e9),
                     injections=[parse_injection(text) for text in injections])
    monitor = PropertyMonitor(source.program, mission, run)
    return run.run(), monitor.results()


def test_monitoring_does_not_change_the_run(arm_file, tmp_path):
    plain = tmp_path / "plain.orc"
    plain.write_text(PID.split("// Signal properties")[0], encoding="utf-8")
    watched, results = _run(arm_file)
    unwatched, _ = _run(plain)
    assert [r.as_dict() for r in watched.robot_tasks] == \
        [r.as_dict() for r in unwatched.robot_tasks]
    assert watched.sim_time_ns == unwatched.sim_time_ns
    assert any(r.kind is PropertyKind.SIGNAL for r in results)


def test_the_api_on_an_auv_fault_that_breaks_the_depth_limit():
    # the depth sensor reads 18 m too shallow from 20 s: the vehicle goes below 30 m while
    # the depth-limit observer (reading the same sensor) sees nothing
    result, verdicts = _run(ROOT / "missions" / "auv_survey.orc", "auv.depth_bias=-18@20",
                            until_s=60.0)
    assert result.status == "timeout"
    by_name = {v.name: v for v in verdicts}
    depth = by_name["safe_depth"]
    assert (depth.verdict, depth.unit) == (Verdict.FALSE, "[m]")
    assert -4.0 < depth.robustness < -1.0
    assert by_name["clear_of_seabed"].verdict is Verdict.TRUE
    # a run cut by --until cannot decide these liveness/safety properties
    assert by_name["leak_surfaces"].verdict is Verdict.UNDECIDED


def test_the_tui_report_lists_the_properties():
    from orccad_app.tui.session import LiveSession

    session = LiveSession(str(ROOT / "missions" / "arm_pid.orc"), None, lambda update: None,
                          speed=None)
    session.execute()
    report = session.report()
    assert "Properties on this run:" in report
    assert "true      signal shoulder_in_range   robustness 0.08" in report


def test_strict_json_of_infinite_and_missing_robustness():
    from orccad_app.properties import PropertyResult

    infinite = PropertyResult("p", PropertyKind.SIGNAL, Verdict.TRUE, float("inf"), "[m]", 3)
    assert infinite.as_dict()["robustness"] is None
    assert infinite.as_dict()["robustness_infinite"] == "+inf"
    none = PropertyResult("q", PropertyKind.SIGNAL, Verdict.UNDECIDED, None, "[m]", 3)
    assert none.as_dict()["robustness_infinite"] is None
    text = json.dumps([infinite.as_dict(), none.as_dict()], allow_nan=False)
    assert _strict(text)[0]["verdict"] == "true"
