"""Missions over Robot-Tasks: run, within, try/catch, on fatal, statuses, both views."""

from __future__ import annotations

import subprocess
import sys

import pytest

from orccad_app.robottask.labels import Phase, PhaseLabel, RtLabel

from orccad_app.diagnostics import OrccadError
from orccad_app.pipeline import load
from tests.robottask.conftest import COMPOSED, Trace, arm_task, mission_automaton

TASKS = arm_task("Track", clauses="""
    module jl : joint_limits(margin = 0.05);
    connect arm.q -> jl.q;
    exception JointLimit from jl : fatal;
    exception Lost from tracking_error(max = 0.2) : abort;""") + \
    arm_task("Home", duration="duration 1 s;").replace("robot arm : arm3dof;", "")


def test_arm_pid_good_end_is_done():
    t = Trace(mission_automaton(load("missions/arm_pid.orc")), ["", "", "TrackPID.good_end"])
    assert t.outputs[0] == {"TrackPID.start"}
    assert t.outputs[2] == {"Tracked"} and t.statuses[2] == "done"


def test_arm_pid_uncaught_type2_fails_with_its_name():
    t = Trace(mission_automaton(load("missions/arm_pid.orc")), ["", "TrackPID.TrackingLost"])
    assert t.statuses == ["running", "failed"] and t.reason == "TrackingLost"
    assert "TrackingLost.raised" in t.outputs[1] and "Tracked" not in t.outputs[1]


def test_arm_pid_type3_aborts_in_the_same_instant():
    t = Trace(mission_automaton(load("missions/arm_pid.orc")), ["", "TrackPID.JointLimit"])
    assert t.statuses == ["running", "aborted"] and t.reason == "JointLimit"


def test_try_catch_recovers_and_the_mission_goes_on(orc):
    source = orc(TASKS + """
mission M {
    output Recovered, End;
    try { run Track(); } catch Lost { emit Recovered; run Home(); }
    emit End;
}""")
    t = Trace(mission_automaton(source), ["", "Track.Lost", "", "Home.good_end"])
    assert t.outputs[1] == {"Lost.raised", "Recovered", "Home.start"}
    assert t.statuses[1] == "running"
    assert t.outputs[3] == {"End"} and t.statuses[3] == "done"


def test_run_within_raises_timeout(orc):
    source = orc(TASKS + """
mission M {
    output Late;
    try { run Track() within 3 s; } catch Timeout { emit Late; }
}""")
    t = Trace(mission_automaton(source), ["@0", "@2", "@3.5"])
    assert t.outputs[2] == {"Timeout.raised", "Late"} and t.statuses[2] == "done"


def test_on_fatal_runs_after_the_abort(orc):
    source = orc(TASKS + """
mission M {
    output Alarm;
    run Track();
    on fatal { emit Alarm; pause; emit Alarm; }
}""")
    t = Trace(mission_automaton(source), ["", "Track.JointLimit", "", ""])
    assert t.outputs[1] == {"JointLimit.raised", "Alarm"}
    assert t.statuses[1:] == ["aborted", "aborted", "aborted"]
    assert t.outputs[2] == {"Alarm"}
    assert t.reactor.finished


def test_fatal_kills_every_task_in_parallel_branches(orc):
    other = arm_task("Other", duration="").replace("robot arm : arm3dof;", "")
    source = orc(TASKS + "robot other : arm3dof;\n" +
                 other.replace("on arm", "on other").replace("arm.", "other.") + """
mission M { par { run Track(); } || { run Other(); } }""")
    automaton = mission_automaton(source, COMPOSED)
    t = Trace(automaton, ["", "Track.JointLimit"])
    assert t.statuses[1] == "aborted"
    assert t.reactor.labels == frozenset()  # no Robot-Task region active any more


def test_composed_view_labels_tell_the_active_task_and_phase(orc):
    source = orc("input Go;\n" + arm_task("A", clauses="precondition Go;") +
                 arm_task("B").replace("robot arm : arm3dof;", "") + """
mission M { run A(); run B(); }""")
    t = Trace(mission_automaton(source, COMPOSED), ["@0"])
    assert PhaseLabel("A", 0, Phase.SYNCHRONIZING) in t.reactor.labels
    t.reactor.react({"Go": None}, 0)
    assert PhaseLabel("A", 0, Phase.ACTIVE) in t.reactor.labels
    t.reactor.react(set(), 2_000_000_000)
    assert RtLabel("B", 1) in t.reactor.labels and RtLabel("A", 0) not in t.reactor.labels


def test_parameterized_task_reused_with_different_arguments(orc):
    from orccad_app.robottask.model import check_tasks
    source = orc(arm_task("T", params="kp: float = 400.0") + """
mission M { run T(kp = 600.0); run T(); run T(kp = 800.0); }""")
    instances = check_tasks(source.program, source.host)
    gains = sorted(i.params["kp"] for i in instances.by_run.values())
    assert gains == [400.0, 600.0, 800.0]
    t = Trace(mission_automaton(source), ["", "T.good_end", "T.good_end", "T.good_end"])
    assert [("T.start" in o) for o in t.outputs] == [True, True, True, False]
    assert t.statuses[-1] == "done"


def test_a_bad_argument_is_located_at_its_run(orc):
    with pytest.raises(OrccadError) as caught:
        orc(arm_task("T", params="kp: float = 400.0") + """
mission M { run T(); run T(kp = -5.0); }""")
    assert "kp" in caught.value.message and caught.value.location.line == 16


def test_react_replays_the_recovery_path_of_the_full_mission(tmp_path):
    script = tmp_path / "recovery.in"
    script.write_text("\nHome.good_end\nTrackPID.TrackingLost\nHome.good_end\n"
                      "TrackPID.good_end\n")
    result = subprocess.run([sys.executable, "-m", "orccad_app.cli", "react",
                             "missions/arm_recovery.orc", "--inputs", str(script), "--jsonl"],
                            capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    import json
    records = [json.loads(line) for line in result.stdout.splitlines()]
    assert "TrackPID.start" in records[1]["outputs"]
    assert {"Retry", "Home.start"} <= set(records[2]["outputs"])
    assert records[2]["values"]["Retry"] == 1
    assert "TrackPID.start" in records[3]["outputs"]
    assert "Finished" in records[4]["outputs"] and records[4]["status"] == "done"


def test_parallel_use_of_one_robot_is_rejected_naming_both_tasks(tmp_path):
    (tmp_path / "c.orc").write_text(TASKS + "mission M { par { run Track(); } || { run Home(); } }")
    result = subprocess.run([sys.executable, "-m", "orccad_app.cli", "compile",
                             str(tmp_path / "c.orc")], capture_output=True, text=True)
    assert result.returncode == 2
    first = result.stderr.splitlines()[0]
    assert "resource conflict" in first and "Track" in first and "Home" in first
    assert "'arm'" in first and "Traceback" not in result.stderr
