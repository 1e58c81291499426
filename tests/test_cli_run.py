"""``orccad run`` and ``orccad tcs`` as a user runs them: reports, exit statuses, traces."""

from __future__ import annotations

import json
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from mcap.reader import make_reader

from orccad_app.cli import main

ROOT = Path(__file__).resolve().parents[1]
PID = str(ROOT / "missions" / "arm_pid.orc")
CT = str(ROOT / "missions" / "arm_computed_torque.orc")
RUN_KEYS = {"status", "reason", "sim_time_s", "wall_time_s", "robot_tasks", "modules",
            "processors", "bus", "exceptions"}
MODULE_KEYS = {"processor", "period_s", "wcet_s", "jobs", "response_time_max_s",
               "response_time_mean_s", "deadline_misses", "preemptions"}


def orccad(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "orccad_app.cli", *args],
                          capture_output=True, text=True, cwd=ROOT)


def _json(capsys, *args: str) -> tuple[int, dict]:
    status = main(list(args))
    return status, json.loads(capsys.readouterr().out)


@pytest.fixture(scope="module")
def pid_report():
    result = orccad("run", "missions/arm_pid.orc", "--json")
    assert result.returncode == 0, result.stderr
    return json.loads(result.stdout)


def test_run_arm_pid_json_is_done_with_every_figure(pid_report):
    report = pid_report
    assert RUN_KEYS <= set(report)
    assert (report["status"], report["reason"], report["sim_time_s"]) == ("done", None, 4.0)
    [task] = report["robot_tasks"]
    assert set(task) == {"name", "args", "start_s", "end_s", "outcome", "tracking_error"}
    assert task["args"] == {"q0": [0.5, 0.5, 0.5], "kp": 400.0, "kv": 40.0}
    assert (task["name"], task["start_s"], task["end_s"], task["outcome"]) == \
        ("TrackPID", 0.0, 4.0, "good_end")
    assert set(task["tracking_error"]) == {"rms", "max", "unit"}
    assert task["tracking_error"]["unit"] == "rad"
    assert set(report["modules"]) == {"TrackPID.traj", "TrackPID.ctrl", "TrackPID.jl",
                                      "TrackPID.tracking_error", "TrackPID.torque_saturation"}
    for module in report["modules"].values():
        assert MODULE_KEYS <= set(module)
    ctrl = report["modules"]["TrackPID.ctrl"]
    assert (ctrl["processor"], ctrl["period_s"], ctrl["wcet_s"], ctrl["jobs"]) == \
        ("cpu0", 0.001, 0.0003, 4000)
    assert report["processors"]["cpu0"]["load"] == pytest.approx(0.45)
    assert (report["bus"]["messages"], report["bus"]["busy_ratio"]) == (0, 0.0)
    assert report["bus"]["classes"]["event"] == {"messages": 0, "queued_mean_s": 0.0,
                                                 "queued_max_s": 0.0}
    assert report["exceptions"] == []
    assert report["wall_time_s"] > 0


def test_computed_torque_mission_has_the_lower_rms_error(pid_report, capsys):
    status, ct = _json(capsys, "run", CT, "--json")
    assert status == 0 and ct["status"] == "done"
    pid_rms = pid_report["robot_tasks"][0]["tracking_error"]["rms"]
    assert ct["robot_tasks"][0]["tracking_error"]["rms"] < pid_rms / 10


def test_tcs_response_times_are_the_measured_worst_cases(pid_report, capsys):
    status, tcs = _json(capsys, "tcs", PID, "--task", "TrackPID", "--format", "json")
    assert status == 0 and tcs["ok"]
    for name, module in tcs["modules"].items():
        if module.get("resource"):
            continue
        measured = pid_report["modules"][f"TrackPID.{name}"]["response_time_max_s"]
        assert measured == pytest.approx(module["response_time_s"], abs=1e-12), name


def test_injected_tracking_lost_ends_failed_with_exit_1(capsys):
    status, report = _json(capsys, "run", PID, "--json", "--inject", "TrackPID.TrackingLost@1.0")
    assert status == 1
    assert (report["status"], report["reason"], report["sim_time_s"]) == \
        ("failed", "TrackingLost", 1.0)
    assert report["exceptions"] == [{"time_s": 1.0, "name": "TrackingLost", "type": 2,
                                     "task": "TrackPID"}]


def test_human_report_and_timeout(capsys):
    status = main(["run", PID, "--until", "0.05"])
    captured = capsys.readouterr()
    assert status == 1
    assert captured.out.startswith("mission ArmPID: timeout")
    assert "TrackPID.ctrl" in captured.out and "Processors: load cpu0" in captured.out
    assert "mission timeout" in captured.err


def test_realtime_reports_lateness(capsys):
    start = time.perf_counter()
    status, report = _json(capsys, "run", PID, "--json", "--until", "0.1", "--realtime", "2")
    assert status == 1 and report["status"] == "timeout"
    assert time.perf_counter() - start >= 0.05  # 0.1 s simulated at 2x real time
    assert set(report["lateness_s"]) == {"median", "p99", "max"}
    assert 0 <= report["lateness_s"]["median"] <= report["lateness_s"]["max"]


@pytest.mark.parametrize("args, message", [
    (["--inject", "Nope@1"], "not an input of mission 'ArmPID'"),
    (["--inject", "Nope"], "bad injection"),
    (["--trace", "out.txt"], "unknown trace format"),
])
def test_bad_run_input_exits_2(args, message, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(["run", PID, *args]) == 2
    assert message in capsys.readouterr().err


@pytest.mark.parametrize("sent, reason", [(signal.SIGINT, "interrupted (Ctrl-C)"),
                                           (signal.SIGTERM, "interrupted (SIGTERM)")])
def test_ctrl_c_keeps_the_trace_valid_prints_the_report_and_exits_130(tmp_path, sent, reason):
    trace = tmp_path / "run.mcap"
    process = subprocess.Popen([sys.executable, "-m", "orccad_app.cli", "run", PID,
                                "--realtime", "1", "--trace", str(trace), "--json"],
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 30
    while not (trace.exists() and trace.stat().st_size) and time.monotonic() < deadline:
        time.sleep(0.05)
    time.sleep(0.5)
    process.send_signal(sent)
    out, err = process.communicate(timeout=30)
    assert process.returncode == 130, err
    report = json.loads(out)
    assert report["status"] == "aborted" and report["reason"] == reason
    assert 0 < report["sim_time_s"] < 4
    with trace.open("rb") as stream:
        topics = {channel.topic for _, channel, _ in make_reader(stream).iter_messages()}
    assert "/ports/TrackPID/ctrl/tau" in topics


def test_tcs_text_and_dot(capsys):
    assert main(["tcs", PID, "--task", "TrackPID"]) == 0
    text = capsys.readouterr().out
    assert "ctrl                 prio  1  R =    0.3 ms" in text
    assert "Deadlock analysis: no cycle of blocking protocols" in text
    assert "Suggested placement on 2 processors" in text
    assert main(["tcs", PID, "--task", "TrackPID", "--format", "dot"]) == 0
    dot = capsys.readouterr().out
    assert dot.startswith('digraph "TrackPID" {') and '"ctrl" -> "arm"' in dot


def test_tcs_names_a_static_deadlock_cycle(tmp_path, capsys):
    text = Path(PID).read_text().replace(
        "connect traj.qd     -> ctrl.qd     : asyn/asyn;",
        "connect traj.qd     -> ctrl.qd     : syn/syn;\n    connect ctrl.tau -> traj.q : syn/syn;")
    path = tmp_path / "stuck.orc"
    path.write_text(text)
    assert main(["tcs", str(path), "--task", "TrackPID"]) == 1
    out = capsys.readouterr().out
    assert "potential deadlock cycles" in out
    assert "ctrl.qd (read, syn/syn)" in out and "traj.q (read, syn/syn)" in out


def test_tcs_unknown_task_is_bad_input(capsys):
    assert main(["tcs", PID, "--task", "Nope"]) == 2
    assert "no Robot-Task named 'Nope'" in capsys.readouterr().err
