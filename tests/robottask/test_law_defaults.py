"""Omitted parts of the time-constrained specification take the law's defaults, and coherence
is real: a Robot-Task that drives nothing, or an observer that nothing can feed, is refused.

The program is the one of issue 18, written from the docs alone: a law, an observer, and no
``module``/``connect`` line. Before, it compiled, passed ``check`` and ran to ``good_end``
with only the observer: nothing wrote ``arm.tau`` and the observer never got ``qd``.
"""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest

from orccad_app.diagnostics import OrccadError
from orccad_app.pipeline import load
from orccad_app.robottask.model import ModuleOrigin, check_tasks

TRACK = """robot arm : arm3dof;

robottask Track(q0: vector = [0.5, 0.5, 0.5]) on arm { duration 2 s; task_function joint_tracking(trajectory = cosine(q0 = q0, omega = pi)); law pid(kp = 400.0, kv = 40.0, ki = 10.0); exception TrackingLost from tracking_error(max = 0.2) : abort; }

mission M {
    run Track();
}
"""


def cli(*args):
    return subprocess.run([sys.executable, "-m", "orccad_app.cli", *args],
                          capture_output=True, text=True)


@pytest.fixture
def track(tmp_path):
    path = tmp_path / "track.orc"
    path.write_text(TRACK, encoding="utf-8")
    return path


def test_tcs_shows_the_law_default_modules_and_connections(track):
    result = cli("tcs", str(track), "--task", "Track")
    assert result.returncode == 0, result.stderr
    out = result.stdout
    assert "traj                 trajectory" in out and "ctrl                 control_law" in out
    for line in ("traj.qd -> ctrl.qd", "traj.qd_dot -> ctrl.qd_dot", "arm.q -> ctrl.q",
                 "arm.qdot -> ctrl.qdot", "ctrl.tau -> arm.tau", "ctrl.e -> tracking_error.e"):
        assert line in out, line
    assert "Coherence: ok" in out


def test_the_default_modules_are_marked_as_the_law_s(track):
    source = load(track)
    instances = check_tasks(source.program, source.host)
    inst = instances.defaults["Track"]
    assert {name: spec.origin for name, spec in inst.modules.items()} == {
        "traj": ModuleOrigin.LAW_DEFAULT, "ctrl": ModuleOrigin.LAW_DEFAULT,
        "tracking_error": ModuleOrigin.OBSERVER}


def test_run_tracks_with_the_default_controller(track):
    result = cli("run", str(track), "--json")
    assert result.returncode == 0, result.stderr
    report = json.loads(result.stdout)
    assert report["status"] == "done"
    assert {"Track.traj", "Track.ctrl", "Track.tracking_error"} <= set(report["modules"])
    error = report["robot_tasks"][0]["tracking_error"]
    assert error is not None and error["max"] < 0.1  # tracked, not fallen under gravity


def write(tmp_path, text):
    path = tmp_path / "m.orc"
    path.write_text(text, encoding="utf-8")
    return path


def test_a_task_that_drives_no_actuator_is_a_located_error(tmp_path):
    text = TRACK.replace(" law pid(kp = 400.0, kv = 40.0, ki = 10.0);", "") \
                .replace(" task_function joint_tracking(trajectory = cosine(q0 = q0, omega = pi));",
                         "").replace("tracking_error(max = 0.2)", "joint_limits(margin = 0.1)")
    with pytest.raises(OrccadError) as caught:
        load(write(tmp_path, text))
    assert "Robot-Task 'Track' does not drive arm.tau" in caught.value.message
    assert caught.value.location.line == 3
    result = cli("check", str(write(tmp_path, text)))
    assert result.returncode == 2
    assert "m.orc:3:" in result.stderr and "does not drive arm.tau" in result.stderr


def test_an_observer_that_can_never_receive_its_inputs_is_a_located_error(tmp_path):
    text = """robot auv : auv;
robottask Hover() on auv {
    duration 2 s;
    module guide : depth_guidance(depth = 5.0) period 100 ms wcet 1 ms;
    module pilot : auv_autopilot period 50 ms wcet 1 ms;
    connect auv.position  -> guide.position;
    connect auv.attitude  -> guide.attitude;
    connect guide.setpoint -> pilot.setpoint;
    connect auv.depth     -> pilot.depth;
    connect auv.attitude  -> pilot.attitude;
    connect auv.velocity  -> pilot.velocity;
    connect pilot.tau     -> auv.tau;
    exception Lost from tracking_error(max = 0.2) : abort;
}
mission M { run Hover(); }
"""
    with pytest.raises(OrccadError) as caught:
        load(write(tmp_path, text))
    message = caught.value.message
    assert "observer tracking_error (tracking_error) of Robot-Task 'Hover' can never receive " \
           "its inputs: it needs e, or q and qd" in message
    assert caught.value.location.line == 13


def test_a_declared_module_keeps_the_law_from_adding_its_kind():
    """arm_pid declares traj and ctrl: no default module is added, its wiring is its own."""
    result = cli("tcs", "missions/arm_pid.orc", "--task", "TrackPID")
    assert result.returncode == 0
    assert "traj_2" not in result.stdout and "ctrl_2" not in result.stdout
    assert "traj.qd_ddot" not in result.stdout  # not connected in arm_pid.orc
    np.testing.assert_equal(result.stdout.count("-> arm.tau"), 1)
