"""Lockstep SIL ends as ``orccad run`` does on every shipped mission with a robot: same status,
Robot-Task runs (outcomes and times), exceptions, tracking errors, module statistics — bit for
bit, since the C Module-Tasks compute what the Python ones do and the timing model is the
same; with computed torque (the C rigid-body dynamics, not Pinocchio's floating-point order)
the tracking errors within 1e-12 relative and everything else exactly. A mission whose
Module-Tasks have no C is refused with the kind and the reason."""

from __future__ import annotations

import math
import subprocess
import sys

import pytest

from orccad_app.sil.generate.layout import NoCImplementation
from orccad_app.sil.lockstep import lockstep

from tests.sil.helpers import MISSIONS, executive_report, plan_of, sil_report

#: (file, mission) of every shipped mission that runs a robot and has C for all its kinds
RUNNABLE = [("arm_pid.orc", None), ("arm_recovery.orc", None), ("arm_retune.orc", None),
            ("arm_interrupts.orc", "ArmInterrupts"), ("arm_interrupts.orc", "ArmInterruptsTight"),
            ("auv_survey.orc", None), ("auv_waypoints.orc", None), ("false_property.orc", None)]
#: the shipped missions with computed torque: tracking errors equal within 1e-12 relative
CLOSE = [("arm_computed_torque.orc", None), ("arm_computed_torque_multirate.orc", None)]


def _close(got, expected, path: str = "") -> None:
    """``got`` equals ``expected``, floats under ``tracking_error`` within 1e-12 relative."""
    if isinstance(expected, dict):
        assert got.keys() == expected.keys(), path
        for key in expected:
            _close(got[key], expected[key], f"{path}.{key}")
    elif isinstance(expected, list):
        assert len(got) == len(expected), path
        for index, (a, b) in enumerate(zip(got, expected)):
            _close(a, b, f"{path}[{index}]")
    elif isinstance(expected, float) and ".tracking_error." in path:
        assert math.isclose(got, expected, rel_tol=1e-12), (path, got, expected)
    else:
        assert got == expected, (path, got, expected)


def test_every_shipped_mission_with_a_robot_is_listed():
    listed = {file for file, _ in RUNNABLE + CLOSE}
    with_robot = {path.name for path in MISSIONS.glob("*.orc")
                  if "robot " in path.read_text() and "mission " in path.read_text()}
    assert with_robot == listed


@pytest.mark.parametrize("file,mission", RUNNABLE)
def test_lockstep_ends_as_the_executive(file, mission):
    assert sil_report(file, mission) == executive_report(file, mission)


@pytest.mark.parametrize("file,mission", CLOSE)
def test_lockstep_with_computed_torque_ends_as_the_executive(file, mission):
    _close(sil_report(file, mission), executive_report(file, mission))


#: a mission with a kind that exists only in Python (the at_goal observer)
WITHOUT_C = """robot arm : arm3dof;
robottask Reach() on arm {
    duration 1 s;
    task_function joint_tracking(trajectory = constant(value = [1.0, 1.0, 1.0]));
    law pid(kp = 400.0, kv = 40.0);
    module traj : trajectory period 1 ms wcet 0.1 ms on cpu0 priority 2;
    module ctrl : control_law period 1 ms wcet 0.3 ms on cpu0 priority 1;
    connect traj.qd -> ctrl.qd;
    connect traj.qd_dot -> ctrl.qd_dot;
    connect arm.q -> ctrl.q;
    connect arm.qdot -> ctrl.qdot;
    connect ctrl.tau -> arm.tau;
    postcondition measure at_goal(tol = 0.01);
}
mission M { run Reach(); }
"""


@pytest.fixture
def without_c(tmp_path):
    path = tmp_path / "reach.orc"
    path.write_text(WITHOUT_C)
    return path


def test_a_kind_without_c_is_refused_with_its_name_and_reason(without_c):
    from orccad_app.mission.plan import plan_mission
    from orccad_app.pipeline import load, select_mission

    source = load(str(without_c))
    plan = plan_mission(source, select_mission(source, None))
    with pytest.raises(NoCImplementation, match="at_goal") as refused:
        with lockstep(plan, str(without_c)):
            pass
    assert "no C implementation" in refused.value.message
    assert refused.value.location is not None


def test_the_command_exits_2_on_a_kind_without_c(without_c):
    done = subprocess.run([sys.executable, "-m", "orccad_app", "sil", str(without_c),
                           "--lockstep"], capture_output=True, text=True, timeout=120)
    assert done.returncode == 2
    assert "at_goal" in done.stderr and "Traceback" not in done.stderr


def test_an_injected_exception_reaches_the_controllers_run():
    """--inject: the tracking-loss exception of arm_pid ends the lockstep run as it ends the
    executive's (same outcome and instant)."""
    from orccad_app.mission.injection import parse_injection

    inject = (parse_injection("TrackPID.TrackingLost@1.0"),)
    expected = executive_report("arm_pid.orc", injections=inject)
    assert expected["status"] == "failed"
    assert sil_report("arm_pid.orc", injections=inject) == expected


def test_lockstep_with_the_executives_timing_options_ends_as_the_executive(tmp_path):
    """--set, --timing, --seed, --scheduler edf, --context-switch-us, --bus-us and
    --inject-from: noisy encoders drawn from the seed, a longer execution time, EDF, overheads
    and a bus delay are the executive's timing model, which lockstep keeps; an input script's
    exception ends both runs at the same instant."""
    from orccad_app.mission.overrides import PlanOverrides
    from orccad_app.session import InputScript

    script = tmp_path / "ce.in"
    script.write_text("@1.7 TrackPID.TrackingLost\n")
    options = dict(overrides=PlanOverrides.from_arguments(["arm.noise_std=1e-3"],
                                                          ["TrackPID.ctrl.wcet_ms=0.5"]),
                   seed=7, until_s=2.0, scheduler="edf", context_switch_ns=5_000,
                   bus_transfer_ns=20_000, script=InputScript.from_file(str(script)))
    expected = executive_report("arm_recovery.orc", **options)
    assert expected["robot_tasks"][1]["outcome"] == "TrackingLost"
    assert expected["injections"][0]["by"] == f"--inject-from {script}"
    assert sil_report("arm_recovery.orc", **options) == expected


def _command(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "orccad_app", *args], capture_output=True,
                          text=True, timeout=120)


def _messages(path) -> list[tuple[str, int, bytes]]:
    from mcap.reader import make_reader

    with open(path, "rb") as stream:
        return [(channel.topic, message.log_time, message.data)
                for _, channel, message in make_reader(stream).iter_messages()]


def test_the_command_writes_the_trace_and_json_of_orccad_run(tmp_path):
    """`orccad sil --lockstep` goes through the run façade: its MCAP trace (the richest
    writer: events, state topics, verdicts) is `orccad run`'s message for message, but for
    the automaton's state numbers — the compiled automaton's, which the controller runs,
    where `orccad run` numbers its lazily built states as the run reaches them: the two
    numberings are one bijection over the run, and the states' source locations are equal.
    Its --json report is `orccad run`'s plus the controller's section."""
    import json

    mission = str(MISSIONS / "arm_recovery.orc")
    common = ["--until", "1.8", "--inject", "TrackPID.TrackingLost@1.6", "--json"]
    sil = _command("sil", mission, "--lockstep", *common, "--trace", str(tmp_path / "sil.mcap"))
    run = _command("run", mission, *common, "--trace", str(tmp_path / "run.mcap"))
    assert sil.returncode == run.returncode == 1, sil.stderr  # a timeout at 1.8 s
    got, expected = json.loads(sil.stdout), json.loads(run.stdout)
    assert got.pop("controller")["mode"] == "lockstep"
    got.pop("wall_time_s"), expected.pop("wall_time_s")
    assert got == expected and got["robot_tasks"][1]["outcome"] == "TrackingLost"
    numbering: dict[int, int] = {}
    sil_messages, run_messages = _messages(tmp_path / "sil.mcap"), _messages(tmp_path / "run.mcap")
    assert len(sil_messages) == len(run_messages)
    for (topic, time, data), (run_topic, run_time, run_data) in zip(sil_messages, run_messages):
        assert (topic, time) == (run_topic, run_time)
        if topic != "/mission/state":
            assert data == run_data, (topic, time)
            continue
        state, run_state = json.loads(data), json.loads(run_data)
        number, run_number = state.pop("state"), run_state.pop("state")
        assert numbering.setdefault(run_number, number) == number, time
        assert state == run_state, time
    assert len(set(numbering.values())) == len(numbering) >= 4  # a bijection


@pytest.mark.parametrize("flag,words", [(["--scheduler", "edf"], "fixed priorities"),
                                        (["--bus-us", "5"], "own memory"),
                                        (["--context-switch-us", "5"], "own context switches")])
def test_what_real_time_does_not_model_is_refused_with_the_reason(flag, words):
    done = _command("sil", str(MISSIONS / "arm_pid.orc"), "--realtime", *flag)
    assert done.returncode == 2 and words in done.stderr and "--lockstep" in done.stderr
    assert "Traceback" not in done.stderr


def test_the_controller_leaves_the_plan_it_is_given_as_it_was():
    """Generating the mission's automaton and starting its controller change nothing of the
    plan they are given (issue 36): the run in the controller runs a copy, with the full
    automaton and sites that start proxies."""
    from orccad_app.reactive.automaton import Automaton
    from orccad_app.sil.generate.automaton import mission_automaton

    plan = plan_of("arm_pid.orc")
    automaton, sites = plan.automaton, list(plan.sites)
    computes = [task.compute for task in plan.tcs.module_tasks]
    mission = mission_automaton(plan)
    assert plan.automaton is automaton and isinstance(mission.automaton, Automaton)
    with lockstep(plan, "arm_pid.orc", automaton=mission) as started:
        assert started.plan is not plan and started.plan.automaton is mission.automaton
        assert all(type(site).__name__ == "RemoteSite" for site in started.plan.sites)
    assert plan.automaton is automaton
    assert all(a is b for a, b in zip(plan.sites, sites, strict=True))
    assert [task.compute for task in plan.tcs.module_tasks] == computes
