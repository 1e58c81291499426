"""Real-time SIL: functional checks only (never timings). The controller's threads run the
Module-Tasks on the wall clock; the mission recovers as in simulation; the measured timing is
reported beside orccad tcs's bounds; a controller killed mid-run fails the run with the reason
and leaves no process; without SCHED_FIFO a warning says why."""

from __future__ import annotations

import os
import signal
import subprocess
import sys

import pytest

from orccad_app.diagnostics import OrccadError
from orccad_app.mission.injection import parse_injection
from orccad_app.sil.realtime import realtime
from orccad_app.sil.runs import ControllerRuns, SilMode

from tests.sil.helpers import MISSIONS, plan_of, session_of
from tests.sil.test_process import _controllers_of, _gone


def _realtime(file: str, mission: str | None = None, **options):
    """The result and timings of a real-time SIL run of shipped ``file``, and its
    controller runs."""
    with ControllerRuns(SilMode.REALTIME, file) as runs:
        result = session_of(file, mission, runs, **options).execute().result
        timings = {t.name: t for t in runs.timings()}
    return result, timings, runs


def test_arm_recovery_recovers_on_the_real_time_threads_as_in_simulation():
    inject = (parse_injection("TrackPID.TrackingLost@2.5"),)
    result, timings, runs = _realtime("arm_recovery.orc", injections=inject)
    assert result.status == "done", result.reason
    assert [(r.name, r.outcome) for r in result.robot_tasks] == [
        ("Home", "good_end"), ("TrackPID", "TrackingLost"), ("Home", "good_end"),
        ("TrackPID", "good_end")]
    assert abs(result.robot_tasks[1].end_ns - 2_500_000_000) <= 2_000_000
    for record in result.robot_tasks:
        assert record.errors.max_abs < 0.1  # the arm tracks on the real threads
    ctrl = timings["TrackPID.ctrl"]
    assert ctrl.released > 4000 and ctrl.lateness_s is not None
    assert ctrl.predicted_s == pytest.approx(0.0003)
    assert timings["Park.ctrl"].released == 0  # never started
    assert _controllers_of(os.getpid()) == []
    assert not os.path.exists(runs.run.shared_memory_path)  # removed once mapped: none left


def test_a_controller_killed_in_real_time_fails_the_run_with_the_reason():
    class Kill:
        sent = False

        def on_reaction(self, now, inputs, outputs, status):
            if now >= 500_000_000 and not self.sent:
                self.sent = True
                os.kill(runs.controller.pid, signal.SIGKILL)

    with ControllerRuns(SilMode.REALTIME, "arm_pid.orc") as runs:
        result = session_of("arm_pid.orc", runs=runs, observers=(Kill(),)).execute().result
        assert _gone(runs.controller.pid)
    assert result.status == "failed"
    assert "killed by SIGKILL" in result.reason
    assert _controllers_of(os.getpid()) == []


def test_what_the_real_time_mode_does_not_run_is_refused_with_the_reason():
    with pytest.raises(OrccadError, match="ramp"):
        with realtime(plan_of("arm_retune.orc"), "arm_retune.orc"):
            pass


def test_a_sporadic_module_task_is_released_by_its_producers_writes():
    """arm_interrupts: the tracking-error observer on cpu1 is released by each write of the
    control law on cpu0 (another thread), never more often than every 2 ms."""
    result, timings, _ = _realtime("arm_interrupts.orc", "ArmInterrupts")
    assert result.status == "done", result.reason
    assert 0 < timings["TrackWatched.watch"].released <= 4.0 / 0.002 + 1


def test_without_sched_fifo_a_warning_says_why():
    env = {**os.environ, "ORCCAD_NO_FIFO": "1"}
    done = subprocess.run([sys.executable, "-m", "orccad_app", "sil",
                           str(MISSIONS / "arm_pid.orc"), "--realtime", "--until", "0.3"],
                          capture_output=True, text=True, timeout=120, env=env)
    assert "SCHED_FIFO is not permitted here (ORCCAD_NO_FIFO is set)" in done.stderr
    assert done.returncode == 1  # timeout at 0.3 s: the run itself went on
    assert "Measured on the controller's threads" in done.stdout
