"""``orccad tcs`` on plan files: the schedulability it prints agrees with ``orccad run``."""

from __future__ import annotations

import json
import time
from pathlib import Path

import pytest

from orccad_app.cli import main

ROOT = Path(__file__).resolve().parents[2]
PID = ROOT / "missions" / "arm_pid.orc"


def _edit(tmp_path: Path, replacements: dict[str, str]) -> str:
    text = PID.read_text(encoding="utf-8")
    for old, new in replacements.items():
        assert old in text, old
        text = text.replace(old, new)
    path = tmp_path / "edited.orc"
    path.write_text(text, encoding="utf-8")
    return str(path)


SYN_MISMATCH = {
    "module traj : trajectory          period 1 ms wcet 0.1 ms on cpu0":
        "module traj : trajectory          period 2 ms wcet 0.1 ms on cpu1",
    "connect traj.qd     -> ctrl.qd     : asyn/asyn;":
        "connect traj.qd     -> ctrl.qd     : syn/syn;",
}
# cpu0: traj 1.38/3 + ctrl 1/2 + the two observers 2 x 0.1/5 = 1.0
FULL_LOAD = {
    "module traj : trajectory          period 1 ms wcet 0.1 ms on cpu0 priority 2":
        "module traj : trajectory          period 3 ms wcet 1.38 ms on cpu0 priority 1",
    "module ctrl : control_law         period 1 ms wcet 0.3 ms on cpu0 priority 1":
        "module ctrl : control_law         period 2 ms wcet 1 ms on cpu0 priority 2",
    "period 5 ms wcet 0.05 ms on cpu0 priority 3": "period 5 ms wcet 0.05 ms on cpu1 priority 3",
}


def _run_json(capsys, *args: str) -> tuple[int, dict]:
    status = main(list(args))
    return status, json.loads(capsys.readouterr().out)


def test_a_syn_rate_mismatch_is_named_and_the_run_misses(tmp_path, capsys):
    path = _edit(tmp_path, SYN_MISMATCH)
    assert main(["tcs", path, "--task", "TrackPID"]) == 1
    out = capsys.readouterr().out
    assert "ctrl" in out and "unschedulable by construction" in out
    assert "'traj' writes every 2 ms" in out
    status, run = _run_json(capsys, "run", path, "--until", "0.1", "--json")
    ctrl = run["modules"]["TrackPID.ctrl"]
    assert ctrl["deadline_misses"] >= 0.9 * ctrl["jobs"]


def test_edf_at_full_load_agrees_with_the_edf_run(tmp_path, capsys):
    path = _edit(tmp_path, FULL_LOAD)
    assert main(["tcs", path, "--task", "TrackPID"]) == 1
    assert "ctrl                 prio  2  R =      — ms" in capsys.readouterr().out
    status, tcs = _run_json(capsys, "tcs", path, "--task", "TrackPID", "--scheduler", "edf",
                            "--json")
    assert status == 0 and tcs["ok"] and tcs["scheduler"] == "edf"
    assert tcs["processors"]["cpu0"]["utilization"] == pytest.approx(1.0)
    _, run = _run_json(capsys, "run", path, "--until", "0.06", "--scheduler", "edf", "--json")
    assert all(m["deadline_misses"] == 0 for m in run["modules"].values())
    _, run = _run_json(capsys, "run", path, "--until", "0.06", "--json")
    assert run["modules"]["TrackPID.ctrl"]["deadline_misses"] > 0


def test_bus_and_context_switches_enter_the_analysis(tmp_path, capsys):
    path = _edit(tmp_path, {"module traj : trajectory          period 1 ms wcet 0.1 ms on cpu0":
                            "module traj : trajectory          period 1 ms wcet 0.1 ms on cpu1"})
    status, tcs = _run_json(capsys, "tcs", path, "--task", "TrackPID", "--bus-us", "50",
                            "--context-switch-us", "5", "--json")
    assert status == 0
    classes = {(m["connection"], m["kind"]) for m in tcs["bus"]["messages"]}
    assert ("traj.qd -> ctrl.qd (asyn/asyn)", "data") in classes
    assert all(m["transfer_s"] == 5e-05 and m["queueing_s"] >= 0 for m in tcs["bus"]["messages"])
    assert tcs["modules"]["ctrl"]["response_time_s"] == pytest.approx(0.31e-3)


def test_json_is_strict(capsys):
    assert main(["tcs", str(PID), "--task", "TrackPID", "--json"]) == 0
    text = capsys.readouterr().out

    def refuse(name):
        raise AssertionError(f"non-finite number {name} in JSON")

    data = json.loads(text, parse_constant=refuse)
    assert data["modules"]["ctrl"]["schedulable"] is True


def test_a_huge_placement_fails_fast_with_a_message(capsys):
    from orccad_app.commands.tcs import MAX_PROCESSORS
    from orccad_app.tcs.placement import MAX_PROCESSORS as PLACEMENT_MAX

    assert MAX_PROCESSORS == PLACEMENT_MAX
    started = time.perf_counter()
    with pytest.raises(SystemExit) as stop:
        main(["tcs", str(PID), "--task", "TrackPID", "--processors", "100000"])
    assert stop.value.code == 2
    assert "expected a whole number in [1, 256], got '100000'" in capsys.readouterr().err
    assert time.perf_counter() - started < 2.0
