"""Run-time arguments of ``run`` (issue 11): what the compiler checks before the run.

A constant argument is evaluated and checked with the control scheme; an argument that reads a
variable or a signal value is a run-time argument: its type and, for a vector literal, its size
are checked against the parameter, which needs a default (the nominal scheme)."""

from __future__ import annotations

import pytest

from orccad_app.lang import ast, diagnose, parse
from orccad_app.lang.run_args import (StaticType, argument_problem, is_constant, param_type,
                                      static_type)

TASKS = """\
robot arm : arm3dof;
robottask Track(kp: float = 400.0, q0: vector = [0.5, 0.5, 0.5], n: int = 2,
                fast: bool = false, nodefault: float) on arm { duration 2 s; }
"""
DECLS = "input W : vector; input F : float; input B : bool; input I : int; input S : string;"


def errors(body: str) -> list[tuple[str, int, int]]:
    text = TASKS + DECLS + "\nmission M {\n" + body + "\n}\n"
    line0 = TASKS.count("\n") + 2
    return [(e.message, e.location.line - line0, e.location.col)
            for e in diagnose(parse(text, "m.orc"))]


def messages(body: str) -> list[str]:
    return [m for m, _, _ in errors(body)]


def _expr(text: str) -> ast.Expr:
    program = parse(f"mission M {{ var x := {text}; }}", "e.orc")
    return program.missions[0].body.statements[0].value


@pytest.mark.parametrize("text, constant", [
    ("1.5", True), ("400.0 * 2", True), ("[1.0, 2.0, pi]", True), ("-3", True),
    ("?W", False), ("k", False), ("400.0 * k", False), ("[?F, 0.0, 1.0]", False),
    ("pre(?F) + 1.0", False),
])
def test_constant_or_run_time(text, constant):
    assert is_constant(_expr(text)) is constant


def test_static_types_of_mission_expressions():
    decls = {"W": ast.SignalDecl(name="W", direction=ast.Direction.INPUT, type="vector"),
             "k": ast.VarDecl(name="k", value=ast.Number(value=2)),
             "f": ast.VarDecl(name="f", value=ast.Number(value=1.5), type=None)}
    kinds = {text: static_type(_expr(text), decls.get) for text in (
        "?W", "k", "k * 2", "k * 2.0", "f", "[k, 1.0]", "?W * 2.0", "k > 1", "not true",
        "\"s\"", "2 s", "[1.0, 2.0] + ?W")}
    assert kinds == {
        "?W": StaticType("vector"), "k": StaticType("int"), "k * 2": StaticType("int"),
        "k * 2.0": StaticType("float"), "f": StaticType("float"),
        "[k, 1.0]": StaticType("vector", 2), "?W * 2.0": StaticType("vector"),
        "k > 1": StaticType("bool"), "not true": StaticType("bool"),
        "\"s\"": StaticType("string"), "2 s": StaticType("duration"),
        "[1.0, 2.0] + ?W": StaticType("vector", 2)}


def test_a_parameter_type_is_declared_or_its_default():
    untyped = ast.Param(name="p", default=ast.Vector(items=(ast.Number(value=1.0),) * 4))
    assert param_type(untyped) == StaticType("vector", 4)
    assert param_type(ast.Param(name="p", type="float")) == StaticType("float")


@pytest.mark.parametrize("body", [
    "var k := 2.0; run Track(kp = 400.0 * k, nodefault = 1.0);",
    "await W; run Track(q0 = ?W, nodefault = 1.0);",
    "await I; run Track(kp = ?I, n = ?I + 1, nodefault = 1.0);",   # an int fits a float
    "await B; run Track(fast = ?B and true, nodefault = 1.0);",
    "await F; run Track(q0 = [?F, 0.0, 1.0], nodefault = 1.0);",
    "await F; run Track(?F, nodefault = 2.0);",                    # positional
])
def test_well_typed_run_time_arguments_pass(body):
    assert messages(body) == []


@pytest.mark.parametrize("body, message, col", [
    ("await B; run Track(kp = ?B, nodefault = 1.0);",
     "Robot-Task 'Track': parameter 'kp' is a float, but this expression is a bool", 20),
    ("await F; run Track(n = ?F, nodefault = 1.0);",
     "Robot-Task 'Track': parameter 'n' is a int, but this expression is a float", 20),
    ("await S; run Track(q0 = ?S, nodefault = 1.0);",
     "Robot-Task 'Track': parameter 'q0' is a vector of 3, but this expression is a string", 20),
    ("await W; run Track(kp = ?W * 2.0, nodefault = 1.0);",
     "Robot-Task 'Track': parameter 'kp' is a float, but this expression is a vector", 20),
    ("await F; run Track(q0 = [?F, 1.0], nodefault = 1.0);",
     "Robot-Task 'Track': parameter 'q0' is a vector of 3 (the size of its default), but this "
     "expression is a vector of 2", 20),
    ("await F; run Track(nodefault = ?F);",
     "Robot-Task 'Track': parameter 'nodefault' gets a run-time value: give it a default in "
     "the robottask (the control scheme is built and checked with it before the run, and with "
     "the actual value when the task starts)", 20),
])
def test_badly_typed_run_time_arguments_are_located_errors(body, message, col):
    assert errors(body) == [(message, 1, col)]


def test_unknown_parameter_and_undeclared_names_are_reported_once():
    assert messages("await F; run Track(kq = ?F, nodefault = 1.0);") == [
        "Robot-Task 'Track' has no parameter 'kq'"]
    assert messages("run Track(kp = k, nodefault = 1.0);") == ["undeclared variable 'k'"]
    assert messages("run Track(kp = F, nodefault = 1.0);") == [
        "signal 'F' used as a value; write ?F for its last value"]


def test_argument_problem_sees_through_untyped_variables():
    param = ast.Param(name="kp", type="float", default=ast.Number(value=1.0))
    decls = {"v": ast.VarDecl(name="v", value=ast.Vector(items=()))}
    assert "is a vector of 0" in argument_problem(param, ast.Name(name="v"), decls.get)
