"""Issue 34, item 11: sizes a user types into `orccad run`, `check` and `--inject` that
overflowed (a Python RuntimeWarning and infinities in the run), crashed (an internal error) or
were echoed whole (half a megabyte in a message) each get a located refusal."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from tests.fuzz.harness import check_outcome, run_orccad

ROOT = Path(__file__).resolve().parents[1]
AUV = str(ROOT / "missions" / "auv_survey.orc")
PID = str(ROOT / "missions" / "arm_pid.orc")
WAYPOINTS = str(ROOT / "missions" / "auv_waypoints.orc")


def _orccad(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-W", "default", "-m", "orccad_app.cli", *args],
                          capture_output=True, text=True, cwd=ROOT, timeout=120)


@pytest.mark.parametrize("setting, message", [
    ("auv.depth.noise_std=1e308", "at most 5 is accepted on auv.depth (the bound of auv's "
                                  "depth_noise_std)"),
    ("auv.position.noise_std=1e308", "at most 1e+06 is accepted on auv.position"),
])
def test_an_overflowing_sensor_noise_is_refused_before_the_run(setting, message):
    done = _orccad("run", AUV, "--until", "2", "--set", setting)
    assert done.returncode == 2, done.stderr
    assert f"--set {setting.replace('1e308', '1e+308')}: a noise standard deviation" \
        in done.stderr and message in done.stderr, done.stderr
    assert "RuntimeWarning" not in done.stderr


def test_an_overflowing_waypoint_fails_the_mission_located_without_a_warning():
    done = _orccad("run", WAYPOINTS, "--until", "5", "--inject",
                   "Waypoint([1e308, 1e308, 5])@0.5")
    assert done.returncode == 1, done.stderr
    assert "RuntimeWarning" not in done.stderr, done.stderr
    assert "auv_waypoints.orc:72:30: run-time argument of GoTo" in done.stderr
    assert "target must be <= 1e+06" in done.stderr


@pytest.mark.parametrize("bound", ["[0, 1e300]", "[1e300, 1e300]", "[0, 31536001]"])
def test_a_signal_property_bound_past_one_year_is_refused_at_parse(tmp_path, bound):
    path = tmp_path / "p.orc"
    text = (ROOT / "missions" / "arm_pid.orc").read_text(encoding="utf-8")
    path.write_text(text + f"property ArmPID.big: always{bound} (norm(arm.e) < 1);\n",
                    encoding="utf-8")
    line = text.count("\n") + 1
    for command in (["check", str(path)], ["run", str(path), "--until", "0.01"]):
        outcome = run_orccad(command)
        check_outcome(outcome)
        assert outcome.status == 2, outcome.err
        assert f"p.orc:{line}:28: error: time bound" in outcome.err
        assert "s is longer than one year (31536000 s)" in outcome.err
    path.write_text(text + "property ArmPID.big: always[0, 31536000] (norm(arm.e) < 1);\n",
                    encoding="utf-8")
    check_outcome(run_orccad(["run", str(path), "--until", "0.01"]))


def test_a_huge_vector_value_is_cut_in_messages_and_in_the_report():
    big = "[" + ", ".join(["1.5"] * 20_000) + "]"
    for value, status, words in ((big, 1, "(20000 components)"),
                                 (big[:-1] + ", nan]", 2,
                                  "characters)' is not a vector value for Waypoint")):
        outcome = run_orccad(["run", WAYPOINTS, "--until", "1", "--inject",
                              f"Waypoint({value})@0.5"])
        check_outcome(outcome)
        assert outcome.status == status, outcome.err
        assert words in outcome.err, outcome.err[:2000]
        assert len(outcome.err) + len(outcome.out) < 5000


@pytest.mark.parametrize("value", ["[1,2", "x", "(1, 2, 3)", "[a, b, c]"])
def test_an_unreadable_injection_value_says_what_is_accepted(value):
    outcome = run_orccad(["run", WAYPOINTS, "--until", "1", "--inject",
                          f"Waypoint({value})@0.5"])
    check_outcome(outcome)
    assert outcome.status == 2
    assert f"'{value}' is not a vector value for Waypoint (finite numbers)" in outcome.err, \
        outcome.err


def test_a_huge_bad_value_in_a_react_script_is_cut_in_the_message(tmp_path):
    script = tmp_path / "big.in"
    script.write_text("Waypoint([" + ",".join(["1.5"] * 100_000) + ",nan])\n",
                      encoding="utf-8")
    outcome = run_orccad(["react", WAYPOINTS, "--inputs", str(script)])
    check_outcome(outcome)
    assert outcome.status == 2
    assert "big.in:1:1: error: '[1.5,1.5," in outcome.err
    assert "(400005 characters)' is not a vector value for Waypoint (finite numbers)" \
        in outcome.err, outcome.err[-300:]
    assert len(outcome.err) < 2000
