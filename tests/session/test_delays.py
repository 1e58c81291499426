"""``orccad run --exchange-us`` and ``--jitter-us``: a real controller's delays in the executive
(orccad_app/executive/delays.py), through the run façade; a marginal mission fails there."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from orccad_app.cli import main
from orccad_app.executive.delays import ControllerDelays
from orccad_app.pipeline import load, select_mission
from orccad_app.session import RunOptions, run_mission

ROOT = Path(__file__).resolve().parents[2]
PID = str(ROOT / "missions" / "arm_pid.orc")


def _report(capsys, *args: str) -> tuple[int, dict]:
    status = main(["run", PID, "--json", *args])
    return status, json.loads(capsys.readouterr().out)


def _verdicts(report: dict) -> dict[str, str]:
    return {p["name"]: p["verdict"] for p in report["properties"]}


def test_the_arm_meets_its_tracking_bound_only_with_the_ideal_exchange(capsys):
    status, ideal = _report(capsys)
    assert status == 0 and _verdicts(ideal)["tracking_bound"] == "true"
    # the arm's ports exchanged every 1 ms at the phase seed 3 draws (just after the
    # releases): the torque reaches the arm about 2 ms after its sensors were sampled
    status, delayed = _report(capsys, "--exchange-us", "1000", "--seed", "3")
    assert status == 1 and delayed["status"] == "done" and _verdicts(delayed)["tracking_bound"] == "false"
    error = delayed["robot_tasks"][0]["tracking_error"]["max"]
    assert error > 1.5 * ideal["robot_tasks"][0]["tracking_error"]["max"]
    _, again = _report(capsys, "--exchange-us", "1000", "--seed", "3")
    assert again["robot_tasks"] == delayed["robot_tasks"]  # deterministic under the seed


def test_release_jitter_shows_in_the_response_times(capsys):
    _, ideal = _report(capsys, "--until", "0.5")
    _, late = _report(capsys, "--until", "0.5", "--jitter-us", "200")
    ctrl, jittered = ideal["modules"]["TrackPID.ctrl"], late["modules"]["TrackPID.ctrl"]
    assert ctrl["response_time_max_s"] == pytest.approx(0.0003)
    assert 0.0003 < jittered["response_time_max_s"] <= 0.0005 + 1e-12
    assert jittered["jobs"] == ctrl["jobs"]  # late, never dropped: the grid is kept


def test_the_session_passes_the_delays_to_the_run():
    source = load(PID)
    mission = select_mission(source, None)
    options = RunOptions(until_s=0.2, delays=ControllerDelays(exchange_ns=1_000_000))
    report = run_mission(source, mission, options)
    assert report.result.status == "timeout"
    ideal = run_mission(source, mission, RunOptions(until_s=0.2))
    delayed, exact = report.result.robot_tasks[0].errors, ideal.result.robot_tasks[0].errors
    assert delayed.count == exact.count and delayed.sum_sq != exact.sum_sq


@pytest.mark.parametrize("args, message", [
    (["--exchange-us", "-1"], "expected microseconds in [0, 1000000]"),
    (["--jitter-us", "2e6"], "expected microseconds in [0, 1000000]"),
    (["--exchange-us", "nan"], "microseconds"),
])
def test_bad_delays_exit_2(args, message, capsys):
    with pytest.raises(SystemExit) as caught:
        main(["run", PID, *args])
    assert caught.value.code == 2 and message in capsys.readouterr().err


def test_sil_in_real_time_refuses_modelled_delays(capsys):
    assert main(["sil", PID, "--realtime", "--exchange-us", "1000"]) == 2
    assert "--exchange-us and --jitter-us model the delays" in capsys.readouterr().err
