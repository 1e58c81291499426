"""Validation of the executive against the control library (issue 6, items 12 b and c).

(b) With zero execution times and ``asyn/asyn`` everywhere, the executive's closed loop is the
direct closed-loop simulation of :mod:`orccad_app.control.closed_loop` — up to the one thing
the executive adds by design: the trajectory's value reaches the control law one period late
(an ``asyn/asyn`` input is read at release, before the same-instant job of the trajectory
writes), and the first control job has no reference yet (no torque during the first period).

(c) On the paper's trajectory, a longer control period or a longer execution time gives a
larger tracking error (RR-1801 §6.2): the executive turns execution time into input/output
delay, which the plant sees exactly (docs/control.md has the full table).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from orccad_app.control.closed_loop import simulate
from orccad_app.control.spec import resolve
from orccad_app.executive import Observer
from orccad_app.mission.run import MissionRun
from orccad_app.plugin_host import PluginHost


class _Samples(Observer):
    """The joint positions the control law reads, one per job."""

    def __init__(self, module: str) -> None:
        self.module = module
        self.q: list[np.ndarray] = []

    def on_read(self, t_ns, module, port, value):
        if module == self.module and port == "q":
            self.q.append(value)


def _direct_pid():
    host = PluginHost.load()
    robot = host.robot_types.get("arm3dof")
    task = resolve(host, "task function", ("joint_tracking", {
        "trajectory": ("cosine", {"q0": [0.5, 0.5, 0.5], "omega": math.pi})}))
    law = resolve(host, "control law", ("pid", {"kp": 400.0, "kv": 40.0, "ki": 10.0}))
    return simulate(law.build(robot, task.build(robot)), 4.0, 1000.0)


def test_zero_execution_times_reproduce_the_direct_closed_loop(plan_file):
    text_edit = {"wcet 0.1 ms on cpu0 priority 2": "wcet 0 ms on cpu0 priority 2",
                 "wcet 0.3 ms on cpu0 priority 1": "wcet 0 ms on cpu0 priority 1",
                 "period 5 ms wcet 0.05 ms": "period 5 ms wcet 0 ms"}
    plan = plan_file("missions/arm_pid.orc", text_edit)
    assert all(task.wcet_ns == 0 for task in plan.tcs.module_tasks if "." in task.name
               and task.kind in ("trajectory", "control_law", "joint_limits"))
    samples = _Samples("TrackPID.ctrl")
    result = MissionRun(plan, observers=[samples]).run()
    direct = _direct_pid()
    assert result.status == "done" and direct.stable
    executive_q = np.array(samples.q)
    assert executive_q.shape == direct.q.shape == (4000, 3)
    # same RMS error to 0.1 %; joint paths within 2.5 mrad (5 % of the largest error): the
    # one-period reference delay, nothing else
    assert result.rms_error() == pytest.approx(direct.rms_error, rel=1e-3)
    assert np.max(np.abs(executive_q - direct.q)) < 2.5e-3
    assert np.max(np.abs(executive_q - direct.q)) < 0.06 * direct.max_error


def _ct_rms(plan_file, period_ms: int, wcet_ms: float) -> float:
    """RMS error of computed torque over 1 s with the given control period and WCET."""
    edits = {"duration 4 s": "duration 1 s",
             "module traj : trajectory          period 1 ms wcet 0.1 ms":
                 f"module traj : trajectory          period {period_ms} ms wcet 0 ms",
             "module ctrl : control_law         period 1 ms wcet 0.4 ms":
                 f"module ctrl : control_law         period {period_ms} ms wcet {wcet_ms:g} ms"}
    result = MissionRun(plan_file("missions/arm_computed_torque.orc", edits)).run()
    assert result.status == "done", result.reason
    return result.rms_error()


def test_longer_periods_and_execution_times_track_worse(plan_file):
    table = {(period, fraction): _ct_rms(plan_file, period, fraction * period)
             for period in (1, 2) for fraction in (0.0, 0.5)}
    for fraction in (0.0, 0.5):
        assert table[(2, fraction)] > 1.5 * table[(1, fraction)]
    for period in (1, 2):
        assert table[(period, 0.5)] > 1.2 * table[(period, 0.0)]
