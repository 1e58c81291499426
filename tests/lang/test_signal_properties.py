"""Signal properties (STL) in the language: parsing, and located errors for what is wrong."""

from __future__ import annotations

import math

import pytest

from orccad_app.diagnostics import OrccadError
from orccad_app.lang import ast
from orccad_app.lang.parser import parse
from orccad_app.pipeline import load

HEADER = """robot arm : arm3dof;
robottask T() on arm {
    duration 1 s;
    task_function joint_tracking(trajectory = cosine(q0 = [0.5, 0.5, 0.5], omega = pi));
    law pid(kp = 400.0, kv = 40.0);
    module traj : trajectory period 1 ms wcet 0.1 ms on cpu0 priority 2;
    module ctrl : control_law period 1 ms wcet 0.3 ms on cpu0 priority 1;
    connect traj.qd -> ctrl.qd : asyn/asyn;
    connect traj.qd_dot -> ctrl.qd_dot : asyn/asyn;
    connect arm.q -> ctrl.q : asyn/asyn;
    connect arm.qdot -> ctrl.qdot : asyn/asyn;
    connect ctrl.tau -> arm.tau : asyn/asyn;
}
mission M { output Done; run T(); emit Done; }
"""


def _formula(text: str) -> ast.Formula:
    return parse(f"property p: {text};").properties[0].formula


def test_the_documented_examples_parse_as_signal_formulas():
    settles = _formula("always (ended(TrackPID) -> eventually[0, 0.5] (norm(arm.e) < 0.005))")
    assert ast.is_signal_formula(settles)
    inner = settles.operand.right
    assert (inner.op, inner.bounds.low_s, inner.bounds.high_s) == ("eventually", 0.0, 0.5)
    compare = inner.operand
    assert isinstance(compare, ast.FCompare) and compare.op == "<"
    assert compare.left == ast.SCall(func="norm", args=(ast.SPort(robot="arm", port="e",
                                                                   loc=compare.left.args[0].loc),),
                                      loc=compare.left.loc)
    assert ast.is_signal_formula(_formula("always (auv.depth < 30.0)"))


def test_bounds_accept_durations_and_until_since_take_bounds():
    formula = _formula("(arm.q[1] >= -pi) until[500 ms, 2 s] done")
    assert formula.op == "until" and (formula.bounds.low_s, formula.bounds.high_s) == (0.5, 2.0)
    assert formula.left.left == ast.SPort(robot="arm", port="q", index=1,
                                          loc=formula.left.left.loc)
    assert formula.left.right.operand.value == pytest.approx(math.pi)
    assert _formula("once[0, 1] started(T) since[0, 2] done").bounds.high_s == 2.0


def test_plain_ltl_is_not_a_signal_formula():
    assert not ast.is_signal_formula(_formula("always (started(T) -> eventually done)"))


@pytest.mark.parametrize("text, message, col", [
    ("always[2, 1] done", r"empty time interval \[2, 1\]", 19),
    ("eventually[0, 1e999] done", "not finite", 23),
    ("always[0, 1.5 ns] done", "not a whole number of nanoseconds", 23),
])
def test_bad_bounds_are_located_errors(text, message, col):
    with pytest.raises(OrccadError, match=message) as error:
        parse(f"property p: {text};")
    assert (error.value.location.line, error.value.location.col) == (1, col)


def test_a_negative_bound_is_a_syntax_error():
    with pytest.raises(OrccadError, match="unexpected '-'"):
        parse("property p: always[-1, 1] done;")


def _load(tmp_path, prop: str):
    path = tmp_path / "m.orc"
    path.write_text(HEADER + prop + "\n", encoding="utf-8")
    return load(path)


@pytest.mark.parametrize("prop, message", [
    ("property M.p: always (rover.q[0] < 1.0);", "unknown robot 'rover'"),
    ("property M.p: always (arm.depth < 1.0);", "robot 'arm' .* has no port 'depth'; its "
                                                "ports: q, qdot, tau, e"),
    ("property M.p: always (arm.q < 1.0);", "compares scalars; this side is a vector of 3"),
    ("property M.p: always (arm.q[3] < 1.0);", r"has 3 components \(\[0\] to \[2\]\)"),
    ("property M.p: always (abs(arm.q) < 1.0);", r"abs\(\) takes a scalar"),
    ("property M.p: always (norm(arm.q + arm.q[0]) < 1.0);", "two vectors of one length"),
    ("property M.p: always (max(arm.q[0]) < 1.0);", "unknown function 'max'"),
    ("property M.p: always (norm(arm.q, arm.qdot) < 1.0);", "takes 1 argument, got 2"),
    ("assume M.a: always (arm.q[0] < 1.0);", "assumption 'a' is a signal formula"),
])
def test_bad_signal_atoms_are_located_errors(tmp_path, prop, message):
    with pytest.raises(OrccadError, match=message) as error:
        _load(tmp_path, prop)
    assert error.value.location.line == HEADER.count("\n") + 1


def test_typed_signal_properties_load(tmp_path):
    source = _load(tmp_path, "property M.p: always (norm(arm.q - arm.qdot) * 2 < 10.0 "
                             "and arm.tau[2] / 2 > -100.0 and sqrt(abs(arm.q[0])) < 2);")
    assert ast.is_signal_formula(source.program.properties[0].formula)
