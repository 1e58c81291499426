"""Type-1 updates that compute (RR-1801 §3.4.2) during a run: a value computed from the current
parameters in the instant of the update, compounding and bounded; a ramp stepped at the
module's releases; trajectory and task-function parameters; a refused computed value ends the
run ``failed`` with the clause's location; every update is logged (old and new value, the ramp)
in the report and the trace."""

from __future__ import annotations

import csv
import json
import math
import re
import subprocess
import sys
from pathlib import Path

import pytest

from orccad_app.mission.injection import Injection
from orccad_app.mission.plan import plan_mission
from orccad_app.mission.run import MissionRun
from orccad_app.pipeline import load, select_mission

ROOT = Path(__file__).resolve().parents[2]

TASK = """robot arm : arm3dof;
robottask Hold(kmax: float = 800.0) on arm {
    duration %s;
    task_function %s;
    law pid(kp = 400.0, kv = 40.0);
    module traj : trajectory  period 1 ms wcet 0.1 ms on cpu0 priority 2;
    module ctrl : control_law period 2 ms wcet 0.3 ms on cpu0 priority 1;
    connect traj.qd     -> ctrl.qd;
    connect traj.qd_dot -> ctrl.qd_dot;
    connect arm.q       -> ctrl.q;
    connect arm.qdot    -> ctrl.qdot;
    connect ctrl.tau    -> arm.tau;
    exception Push from tracking_error(max = 10.0) : adjust %s;  // only injected
}
mission M { run Hold(); }
"""
HOLD = "joint_tracking(trajectory = constant(value = [0.0, 0.0, 0.0]))"


def _plan(tmp_path: Path, update: str, duration: str = "1 s", function: str = HOLD):
    path = tmp_path / "m.orc"
    text = TASK % (duration, function, update)
    if function.startswith("cartesian"):  # the reference ports are xd, xd_dot
        text = re.sub(r"\.qd(_dot)?\b", r".xd\1", text)
    path.write_text(text, encoding="utf-8")
    source = load(path)
    return plan_mission(source, select_mission(source, None)), path


def _adjust_at(path: Path) -> str:
    """``FILE:LINE:COL`` of the ``adjust`` clause in ``path``."""
    lines = path.read_text(encoding="utf-8").splitlines()
    number = next(i for i, line in enumerate(lines, 1) if "adjust" in line)
    return f"{path}:{number}:{lines[number - 1].index('adjust') + 1}"


def _pushes(*times_ms: float) -> list[Injection]:
    return [Injection("Hold.Push", int(t * 1_000_000)) for t in times_ms]


def _sampled(plan, module: str, param: str, times_ms: list[float], injections, **options):
    """The run's result and ``module.param`` at each of ``times_ms`` (after that instant's
    events: sampled just before the next millisecond)."""
    run = MissionRun(plan, injections=injections, **options)
    samples: dict[float, object] = {}
    compute = plan.tcs.module(module)
    for t in times_ms:
        run.kernel.schedule(int(t * 1e6) + 999_999, 5,
                            lambda _, t=t: samples.__setitem__(
                                t, compute.compute.get_param(param)))
    return run.run(), samples


def test_a_computed_update_compounds_and_is_bounded_by_its_min(tmp_path):
    plan, _ = _plan(tmp_path, "ctrl.kp = min(ctrl.kp * 1.5, kmax)")
    result, seen = _sampled(plan, "Hold.ctrl", "kp", [15, 25, 35, 45, 55],
                            _pushes(10, 20, 30, 40, 50))
    assert result.status == "done"
    assert [seen[t] for t in (15, 25, 35, 45, 55)] == [600.0, 800.0, 800.0, 800.0, 800.0]
    updates = [(e.time_ns, e.update.old, e.update.new) for e in result.exceptions]
    assert updates == [(10_000_000, 400.0, 600.0), (20_000_000, 600.0, 800.0),
                       (30_000_000, 800.0, 800.0), (40_000_000, 800.0, 800.0),
                       (50_000_000, 800.0, 800.0)]


def test_a_ramp_moves_the_parameter_at_each_release_of_the_module(tmp_path):
    plan, _ = _plan(tmp_path, "ctrl.kv = ramp(10.0, 50.0, 100 ms)")
    result, seen = _sampled(plan, "Hold.ctrl", "kv", [5, 100, 101, 102, 125, 150, 199, 200, 300],
                            _pushes(100))
    assert result.status == "done"
    # ctrl is released every 2 ms from 0: the value is the ramp's at those instants
    assert seen[5] == 40.0  # nominal, before the update
    assert seen[100] == seen[101] == 10.0
    assert seen[102] == pytest.approx(10.0 + 40.0 * 2 / 100)
    assert seen[125] == pytest.approx(10.0 + 40.0 * 24 / 100)  # last release: 124 ms
    assert seen[150] == pytest.approx(30.0)
    assert seen[199] == pytest.approx(10.0 + 40.0 * 98 / 100)
    assert seen[200] == seen[300] == 50.0
    [record] = result.exceptions
    assert (record.update.old, record.update.new) == (40.0, 10.0)
    ramp = record.update.ramp
    assert (ramp.start, ramp.end, ramp.duration_ns) == (10.0, 50.0, 100_000_000)


def test_a_new_update_replaces_a_running_ramp_and_a_ramp_can_start_from_the_current_value(
        tmp_path):
    plan, _ = _plan(tmp_path, "ctrl.kv = ramp(ctrl.kv, ctrl.kv + 40.0, 100 ms)")
    result, seen = _sampled(plan, "Hold.ctrl", "kv", [59, 60, 159, 160, 250], _pushes(10, 60))
    assert seen[59] == pytest.approx(40.0 + 40.0 * 48 / 100)
    # at 60 ms the first ramp's step (60.0), then the second ramp from there to 100
    assert seen[60] == pytest.approx(60.0)
    assert seen[159] == pytest.approx(60.0 + 40.0 * 98 / 100)
    assert seen[160] == seen[250] == pytest.approx(100.0)
    assert [e.update.ramp.end for e in result.exceptions] == [80.0, pytest.approx(100.0)]


def test_a_ramp_stops_with_its_task(tmp_path):
    plan, _ = _plan(tmp_path, "ctrl.kv = ramp(10.0, 50.0, 1 s)", duration="100 ms")
    run = MissionRun(plan, injections=_pushes(50))
    result = run.run()
    assert result.status == "done" and result.sim_time_ns == 100_000_000
    assert not run._updates._ramps


def test_trajectory_and_task_function_parameters_are_updated(tmp_path):
    cosine = "joint_tracking(trajectory = cosine(q0 = [0.5, 0.5, 0.5], omega = pi))"
    plan, _ = _plan(tmp_path, "traj.omega = traj.omega / 2.0", function=cosine)
    result, seen = _sampled(plan, "Hold.traj", "omega", [5, 15], _pushes(10))
    assert seen[5] == pytest.approx(3.141592653589793)
    assert seen[15] == pytest.approx(3.141592653589793 / 2)
    function = plan.tcs.module("Hold.traj").compute.task_function
    at_s = function.trajectory.at_s  # when the update applied (task time)
    reference = function.reference(1.0).pos
    # the frequency changes from the phase reached (the set-point stays continuous): issue 28
    phase = 3.141592653589793 * at_s + 3.141592653589793 / 2 * (1.0 - at_s)
    assert 0 < at_s < 0.02
    assert reference == pytest.approx([0.5 * (1 + math.cos(phase))] * 3, abs=1e-12)
    cartesian = "cartesian_tracking(trajectory = constant(value = [0.3, 0.0, 0.5]))"
    plan, _ = _plan(tmp_path, "ctrl.damping = ramp(0.0, 0.1, 50 ms)", function=cartesian)
    result, seen = _sampled(plan, "Hold.ctrl", "damping", [5, 25, 60], _pushes(10))
    assert result.status == "done"
    assert (seen[5], seen[25], seen[60]) == (0.01, pytest.approx(0.1 * 14 / 50), 0.1)
    assert plan.tcs.module("Hold.ctrl").compute.law.task_function.damping == 0.1


def test_a_refused_computed_value_ends_the_run_failed_with_its_location(tmp_path):
    plan, path = _plan(tmp_path, "ctrl.kp = ctrl.kp - 250.0")
    result = MissionRun(plan, injections=_pushes(10, 20)).run()
    assert (result.status, result.sim_time_ns) == ("failed", 20_000_000)
    assert result.reason == (f"{_adjust_at(path)}: type-1 update of Hold.ctrl.kp by Push at "
                             f"t = 0.02 s: pid: kp must be > 0, got -100.0")
    # the first one applied; the second is recorded without an update
    assert [(e.time_ns, e.update and e.update.new) for e in result.exceptions] == \
        [(10_000_000, 150.0), (20_000_000, None)]
    assert plan.tcs.module("Hold.ctrl").compute.get_param("kp") == 150.0  # never clamped


def test_a_ramp_whose_end_is_refused_fails_when_it_is_applied(tmp_path):
    plan, path = _plan(tmp_path, "ctrl.kv = ramp(ctrl.kv, ctrl.kv - 50.0, 1 s)")
    result = MissionRun(plan, injections=_pushes(10)).run()
    assert result.status == "failed"
    assert "the end of its ramp: control_law: kv must be > 0, got -10.0" in result.reason
    assert result.reason.startswith(f"{_adjust_at(path)}: ")


def _orccad(*args: str, cwd: Path = ROOT) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "orccad_app.cli", *args], capture_output=True,
                          text=True, cwd=cwd, timeout=600)


def test_the_shipped_mission_logs_every_update_in_the_report_and_the_trace(tmp_path):
    trace = tmp_path / "retune.csv"
    text = _orccad("run", "missions/arm_retune.orc", "--trace", str(trace))
    assert text.returncode == 0, text.stderr
    assert "0.100 s  Drift (type 1, TrackSoft): TrackSoft.ctrl.kp 100 -> 150" in text.stdout
    assert "0.350 s  Drift (type 1, TrackSoft): TrackSoft.ctrl.kp 759.375 -> 800" in text.stdout
    assert ("0.105 s  Lagging (type 1, TrackSoft): TrackSoft.ctrl.ki 0 -> ramp 0 -> 20 over "
            "1 s") in text.stdout
    with trace.open(encoding="utf-8") as stream:
        rows = [r for r in csv.DictReader(stream) if r["event"] in ("update", "param")]
    updates = [(r["time_ns"], r["port"], json.loads(r["value"])) for r in rows
               if r["event"] == "update"]
    assert updates[0] == ("100450000", "kp", {"exception": "Drift", "task": "TrackSoft",
                                              "old": 100.0, "new": 150.0, "ramp": None})
    assert updates[1] == ("105500000", "ki", {"exception": "Lagging", "task": "TrackSoft",
                                              "old": 0.0, "new": 0.0,
                                              "ramp": {"start": 0.0, "end": 20.0,
                                                       "duration_s": 1.0}})
    kp = [json.loads(r["value"])["new"] for r in rows if r["event"] == "update"
          and r["port"] == "kp"]
    assert kp[:6] == [150.0, 225.0, 337.5, 506.25, 759.375, 800.0] and max(kp) == 800.0
    ki = [(r["time_ns"], r["value"]) for r in rows if r["event"] == "param" and r["port"] == "ki"]
    assert ki == [("105500000", "0.0"), ("1105500000", "20.0")]  # the ramp's start and end
    report = json.loads(_orccad("run", "missions/arm_retune.orc", "--json").stdout)
    first = report["exceptions"][0]
    assert first["update"] == {"module": "TrackSoft.ctrl", "param": "kp", "old": 100.0,
                               "new": 150.0, "ramp": None}


def test_an_mcap_trace_has_the_updates_on_their_topic_and_the_log(tmp_path):
    from mcap.reader import make_reader

    trace = tmp_path / "retune.mcap"
    run = _orccad("run", "missions/arm_retune.orc", "--until", "0.2", "--trace", str(trace))
    assert run.returncode == 1, run.stderr  # timeout at 0.2 s
    with trace.open("rb") as stream:
        messages = [(channel.topic, json.loads(message.data)) for _, channel, message
                    in make_reader(stream).iter_messages(topics=["/orccad/update", "/log"])]
    updates = [m for topic, m in messages if topic == "/orccad/update"]
    assert [(u["param"], u["exception"], json.loads(u["update_json"])["new"]) for u in updates] \
        == [("kp", "Drift", 150.0), ("ki", "Lagging", 0.0), ("kp", "Drift", 225.0)]
    logs = [m["message"] for topic, m in messages if topic == "/log"]
    assert "type-1 update by Lagging: TrackSoft.ctrl.ki 0.0 -> ramp 0.0 -> 20.0 over 1.0 s" in logs
