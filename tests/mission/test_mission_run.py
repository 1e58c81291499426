"""Missions in the loop: the automaton starts, kills and retunes Module-Tasks; observers'
events, injections and timers reach it; statuses, Robot-Task records, exceptions."""

from __future__ import annotations

import pytest

from orccad_app.diagnostics import OrccadError
from orccad_app.executive import EventLog
from orccad_app.lang.ast_robottask import ExceptionType
from orccad_app.mission.injection import Injection, parse_injection
from orccad_app.mission.result import TaskOutcome
from orccad_app.mission.run import MissionRun
from orccad_app.tcs import response_time_analysis

PID = "missions/arm_pid.orc"


def _run(plan, **options):
    log = EventLog()
    result = MissionRun(plan, observers=[log], **options).run()
    return result, log


def _events(log, hook, module=None):
    return [e for e in log.events if e[0] == hook and (module is None or e[2] == module)]


def test_arm_pid_runs_its_robot_task_to_the_good_end(pid_run):
    plan, result = pid_run
    assert (result.status, result.reason, result.sim_time_ns) == ("done", None, 4_000_000_000)
    [record] = result.robot_tasks
    assert (record.name, record.start_ns, record.end_ns, record.outcome) == \
        ("TrackPID", 0, 4_000_000_000, "good_end")
    assert result.outputs == [(4_000_000_000, "Tracked", None)]
    ctrl = result.stats.tasks["TrackPID.ctrl"]
    assert ctrl.completed == 4000 and ctrl.deadline_misses == 0
    assert result.stats.tasks["TrackPID.jl"].completed == 800
    assert result.exceptions == []


def test_measured_worst_responses_equal_the_response_time_analysis(pid_run):
    plan, result = pid_run
    analysis = response_time_analysis(plan.tcs.module_tasks)
    for name, stats in result.stats.tasks.items():
        assert stats.response_max_ns == analysis[name].response_ns, name


def test_tracking_error_matches_the_direct_closed_loop_figure(pid_run):
    # docs/control.md: PID at 1 kHz, RMS 2.340e-02 rad, max 4.467e-02 rad
    _, result = pid_run
    error = result.robot_tasks[0].errors.summary()
    assert error["rms"] == pytest.approx(2.340e-2, rel=2e-3)
    assert error["max"] == pytest.approx(4.467e-2, rel=5e-3)


def test_computed_torque_tracks_better_than_pid(pid_run, plan_file):
    ct = MissionRun(plan_file("missions/arm_computed_torque.orc")).run()
    assert ct.status == "done"
    assert ct.rms_error() < pid_run[1].rms_error() / 10


def test_injected_tracking_lost_fails_the_mission_at_that_instant(plan_file):
    result, log = _run(plan_file(PID), injections=[Injection("TrackPID.TrackingLost",
                                                             1_000_000_000)])
    assert (result.status, result.reason, result.sim_time_ns) == \
        ("failed", "TrackingLost", 1_000_000_000)
    assert result.robot_tasks[0].outcome == "TrackingLost"
    assert [(e.name, e.type.number, e.task) for e in result.exceptions] == \
        [("TrackingLost", 2, "TrackPID")]
    assert result.exit_status == 1


def test_outcomes_and_exception_types_stay_typed_until_serialized(plan_file):
    """A real run's records hold TaskOutcome and ExceptionType members, never a plain word or
    number; their JSON is the words and numbers of before (``TrackingLost``, 1, 2)."""
    plan = plan_file(PID)
    result, _ = _run(plan, injections=[Injection("TrackPID.Saturated", 200_000_000),
                                       Injection("TrackPID.TrackingLost", 1_000_000_000)])
    [record] = result.robot_tasks
    assert type(record.end) is TaskOutcome and record.end is TaskOutcome.RAISED
    assert record.exception == "TrackingLost" and record.as_dict()["outcome"] == "TrackingLost"
    assert [type(e.type) for e in result.exceptions] == [ExceptionType, ExceptionType]
    assert [e.type for e in result.exceptions] == [ExceptionType.ADJUST, ExceptionType.ABORT]
    assert [type(e.as_dict()["type"]) for e in result.exceptions] == [int, int]
    assert [e.as_dict()["type"] for e in result.exceptions] == [1, 2]
    raisers = [r for found in plan.roles.raisers.values() for r in found]
    assert raisers and all(type(r.type) is ExceptionType for r in raisers)


def test_a_finished_task_ends_good_end_typed(pid_run):
    assert [(r.end, type(r.end)) for r in pid_run[1].robot_tasks] == \
        [(TaskOutcome.GOOD_END, TaskOutcome)]


def test_type1_exception_retunes_the_running_module(plan_file):
    plan = plan_file(PID)
    result, log = _run(plan, injections=[Injection("TrackPID.Saturated", 500_000_000)])
    assert result.status == "done"
    assert [(e.name, e.type.number) for e in result.exceptions] == [("Saturated", 1)]
    assert _events(log, "on_param") == [("on_param", 500_000_000, "TrackPID.ctrl", "kp", "200.0")]
    assert plan.tcs.module("TrackPID.ctrl").compute.params["kp"] == 200.0


def test_fatal_exception_aborts_the_mission(plan_file):
    result, _ = _run(plan_file(PID), injections=[Injection("TrackPID.JointLimit", 200_000_000)])
    assert (result.status, result.reason) == ("aborted", "JointLimit")
    assert [(e.name, e.type.number) for e in result.exceptions] == [("JointLimit", 3)]


def test_a_mission_still_running_at_until_times_out(plan_file):
    result, log = _run(plan_file(PID), until_ns=300_000_000)
    assert (result.status, result.sim_time_ns) == ("timeout", 300_000_000)
    assert result.robot_tasks[0].outcome == "running" and result.robot_tasks[0].end_ns is None


def test_modules_start_phase_by_phase(plan_text, hold_task):
    text = hold_task % "    precondition measure at_rest(tol = 0.05) within 1 s;" + \
        "mission M { run Hold(); }"
    result, log = _run(plan_text(text))
    assert result.status == "done"
    activations = [(e[1], e[2]) for e in _events(log, "on_activate")]
    # phase 2 at 0: the measuring observer alone; its first event (0.1 ms, its WCET) starts
    # phase 3: every module.
    assert activations[0] == (0, "Hold.at_rest")
    assert sorted(activations[1:]) == [(100_000, "Hold.ctrl"), (100_000, "Hold.traj")]
    assert result.robot_tasks[0].outcome == "good_end"
    kills = {e[2] for e in _events(log, "on_kill")}
    assert kills == set()  # the mission ends with the task: nothing left to kill


def test_a_robot_task_run_again_restarts_afresh(plan_text, hold_task):
    text = hold_task % "    exception Saturated from torque_saturation : adjust ctrl.kp = 200.0;" \
        + "mission M { repeat 2 { run Hold(); } }"
    plan = plan_text(text)
    result, log = _run(plan, injections=[Injection("Hold.Saturated", 50_000_000)])
    assert result.status == "done"
    assert [(r.start_ns, r.end_ns, r.outcome) for r in result.robot_tasks] == \
        [(0, 200_000_000, "good_end"), (200_000_000, 400_000_000, "good_end")]
    assert [e[1] for e in _events(log, "on_activate", "Hold.ctrl")] == [0, 200_000_000]
    assert [e[1] for e in _events(log, "on_kill", "Hold.ctrl")] == [200_000_000]
    # the second run starts with the nominal gain, not the first run's adjustment
    assert plan.tcs.module("Hold.ctrl").compute.params["kp"] == 400.0


def test_modules_block_each_other_the_run_stops_naming_them(plan_text, hold_task):
    text = hold_task.replace("connect traj.qd     -> ctrl.qd;",
                             "connect traj.qd     -> ctrl.qd : syn/syn;\n"
                             "    connect ctrl.tau    -> traj.q  : syn/syn;") % "" + \
        "mission M { run Hold(); }"
    result, log = _run(plan_text(text))
    assert result.status == "failed"
    assert "deadlock at t = 0 ns" in result.reason
    assert "Hold.ctrl.qd (read, syn/syn) waits for Hold.traj" in result.reason
    assert "Hold.traj.q (read, syn/syn) waits for Hold.ctrl" in result.reason
    assert _events(log, "on_deadlock")


@pytest.mark.parametrize("text, expected", [
    ("Stop@2.5", Injection("Stop", 2_500_000_000)),
    ("Gripper(0.7)@1", Injection("Gripper", 1_000_000_000, 0.7)),
    ("Count(3) @ 0.001s", Injection("Count", 1_000_000, 3)),
    ("TrackPID.TrackingLost@1.0", Injection("TrackPID.TrackingLost", 1_000_000_000)),
])
def test_injections_are_parsed(text, expected):
    assert parse_injection(text) == expected


@pytest.mark.parametrize("text", ["Stop", "Stop@", "Stop@-1", "1x@2", "Stop(a)@x"])
def test_bad_injections_are_reported(text):
    with pytest.raises(OrccadError, match="bad injection"):
        parse_injection(text)


def test_an_injection_must_name_an_input(plan_file):
    with pytest.raises(OrccadError, match="not an input of mission 'ArmPID'"):
        MissionRun(plan_file(PID), injections=[Injection("Stop", 0)])


def test_an_event_after_the_instants_reaction_gets_its_own_reaction_at_once(plan_text,
                                                                           hold_task):
    # the injection and the tick react first at t = 0; the zero-time observer then fires at
    # t = 0 too: phase 3 must start at 0, not at the next tick.
    text = "input Go;\n" + hold_task % (
        "    module rest : at_rest(tol = 0.05) period 5 ms wcet 0 ms on cpu0;\n"
        "    connect arm.qdot -> rest.qdot;\n"
        "    precondition measure rest within 1 s;") + "mission M { run Hold(); }"
    result, log = _run(plan_text(text), injections=[Injection("Go", 0)])
    assert result.status == "done"
    assert [(e[1], e[2]) for e in _events(log, "on_activate")] == \
        [(0, "Hold.rest"), (0, "Hold.traj"), (0, "Hold.ctrl")]


def test_a_diverging_plant_fails_the_run_with_its_message(plan_file, monkeypatch):
    from orccad_app.executive import MujocoPlant, PlantDivergenceError

    original = MujocoPlant._check

    def check(self, time_ns):
        original(self, time_ns)
        if time_ns >= 100_000_000:
            raise PlantDivergenceError(f"plant '{self.name}' diverged before t = {time_ns} ns")

    monkeypatch.setattr(MujocoPlant, "_check", check)
    result, _ = _run(plan_file(PID))
    assert (result.status, result.exit_status) == ("failed", 1)
    assert result.reason == "plant 'arm' diverged before t = 100000000 ns"
    assert result.sim_time_ns == 100_000_000 and result.robot_tasks[0].outcome == "running"


class _AtInstant:
    """Calls ``action(run)`` once, from the first reaction at or after ``t_ns``."""

    def __init__(self, t_ns, action):
        self.t_ns, self.action, self.run, self.done = t_ns, action, None, False

    def on_reaction(self, t_ns, inputs, outputs, status):
        if not self.done and t_ns >= self.t_ns:
            self.done = True
            self.action(self.run)


def test_an_input_injected_from_a_callback_reacts_in_that_instant(plan_file):
    hook = _AtInstant(1_000_000_000, lambda run: run.inject("TrackPID.TrackingLost"))
    run = MissionRun(plan_file(PID), observers=[hook])
    hook.run = run
    result = run.run()
    assert (result.status, result.reason, result.sim_time_ns) == \
        ("failed", "TrackingLost", 1_000_000_000)
    with pytest.raises(OrccadError, match="not an input"):
        run.inject("Nope")


def test_abort_from_a_callback_ends_the_run_aborted(plan_file):
    seen = []
    hook = _AtInstant(500_000_000, lambda run: (seen.append(run.phases), run.abort("user")))
    run = MissionRun(plan_file(PID), observers=[hook])
    hook.run = run
    result = run.run()
    assert (result.status, result.reason, result.sim_time_ns) == ("aborted", "user", 500_000_000)
    assert seen == [{0: 3}] and not result.interrupted
