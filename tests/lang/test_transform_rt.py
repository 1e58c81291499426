"""Robot-Task blocks become one RobotTask node; durations become integer nanoseconds."""

from __future__ import annotations

import pytest

from orccad_app.diagnostics import OrccadError
from orccad_app.lang import ast, parse
from orccad_app.lang.transform_rt import UNIT_NS, duration_to_ns
from tests.lang import examples

MS = 1_000_000


@pytest.fixture(scope="module")
def track() -> ast.RobotTask:
    return parse(examples.TRACK_PID, "t.orc").robottask("TrackPID")


def test_header(track):
    assert (track.name, track.robot) == ("TrackPID", "arm")
    q0, kp = track.params
    assert (q0.name, q0.type, [i.value for i in q0.default.items]) == (
        "q0", "vector", [0.5, 0.5, 0.5])
    assert (kp.name, kp.type, kp.default.value) == ("kp", "float", 400.0)
    assert track.param("kp") is kp and track.param("nope") is None


def test_control_law_and_task_function(track):
    assert track.duration_ns == 4_000_000_000
    tf = track.task_function
    assert tf.func == "joint_tracking"
    trajectory = tf.arg("trajectory").value
    assert trajectory.func == "cosine" and trajectory.arg("omega").value.text == "pi"
    assert trajectory.arg("q0").value == ast.Name(name="q0",
                                                  loc=trajectory.arg("q0").value.loc)
    assert [(a.name, a.value.value if hasattr(a.value, "value") else a.value.name)
            for a in track.law.args] == [("kp", "kp"), ("kv", 40.0), ("ki", 10.0)]


def test_modules(track):
    traj, ctrl, jl = track.modules
    assert (traj.name, traj.kind, traj.args) == ("traj", "trajectory", ())
    assert (traj.period_ns, traj.wcet_ns, traj.bcet_ns) == (2 * MS, 300_000, None)
    assert (traj.processor, traj.priority) == ("cpu0", 2)
    assert ctrl.priority == 1 and jl.args[0].name == "margin"
    assert track.module("jl") is jl


def test_module_timing_is_optional_and_in_any_order():
    task = parse("robot a : k; robottask T() on a { module m : k priority 3 bcet 1 us "
                 "on cpu1 wcet 2 us period 1 ms; module n : k; }", "t.orc").robottasks[0]
    m, n = task.modules
    assert (m.period_ns, m.wcet_ns, m.bcet_ns, m.processor, m.priority) == (
        MS, 2000, 1000, "cpu1", 3)
    assert (n.period_ns, n.processor, n.priority) == (None, None, None)


def test_connections(track):
    first = track.connections[0]
    assert (first.source.component, first.source.port) == ("traj", "qd")
    assert (first.target.component, first.target.port, first.protocol) == (
        "ctrl", "qd", "asyn/syn")
    default = parse("robottask T() on a { connect a.b -> c.d; }", "t.orc").robottasks[0]
    assert default.connections[0].protocol == ast.DEFAULT_PROTOCOL == "asyn/asyn"


def test_conditions_and_exceptions(track):
    sync, measure = track.preconditions
    assert sync == ast.SignalPrecondition(signal="ArmReady", loc=sync.loc)
    assert measure.observer.func == "at_rest" and measure.within_ns == 2_000_000_000
    limit, lost, saturated = track.exceptions
    assert (limit.source.func, limit.source.args, limit.type) == ("jl", (),
                                                                  ast.ExceptionType.FATAL)
    assert lost.type is ast.ExceptionType.ABORT and lost.source.arg("max").value.value == 0.2
    assert saturated.type is ast.ExceptionType.ADJUST
    assert (saturated.adjust.target.component, saturated.adjust.target.port) == ("ctrl", "kp")
    assert saturated.adjust.value.value == 200.0
    post_measure, post_emit = track.postconditions
    assert post_measure.observer.func == "at_goal" and post_emit.signal == "Tracked"
    assert track.raisable() == ("TrackingLost", "at_rest_timeout")


def test_empty_robottask_and_source_position(track):
    task = parse("robottask T() on a { }", "t.orc").robottasks[0]
    assert (task.params, task.duration_ns, task.law, task.modules) == ((), None, None, ())
    assert (track.loc.line, track.loc.col, track.loc.end_line) == (1, 1, 22)
    assert (track.modules[1].loc.line, track.modules[1].loc.col) == (8, 5)


@pytest.mark.parametrize("text, ns", [
    ("2 s", 2_000_000_000), ("1.5 ms", 1_500_000), ("250 us", 250_000), ("10 ns", 10),
    ("1e-3 s", 1_000_000), ("0.3ms", 300_000), ("3e2 ns", 300)])
def test_duration_to_ns(text, ns):
    assert duration_to_ns(text) == ns and isinstance(duration_to_ns(text), int)


def test_duration_must_be_whole_nanoseconds():
    with pytest.raises(OrccadError, match="whole number of nanoseconds"):
        duration_to_ns("0.5 ns")
    assert UNIT_NS["s"] == 10**9
