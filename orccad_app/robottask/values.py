"""Values of a Robot-Task: its parameters and the arguments of its clauses.

A ``robottask`` block is parameterized (``TrackPID(q0: vector = [...], kp: float = 400.0)``);
each ``run TrackPID(kp = 600.0)`` gives arguments. :func:`task_arguments` binds them (defaults,
named and positional arguments, types checked) and :func:`evaluate` computes the value of a
clause's expression in that binding: numbers, vectors (lists of floats), strings, booleans,
durations (integer ns), arithmetic, and calls as *call forms* ``(name, {arg: value})`` that the
control library resolves (``cosine(q0 = q0, omega = pi)``).
"""

from __future__ import annotations

import operator
from typing import Any, Mapping

from orccad_app.diagnostics import OrccadError
from orccad_app.lang import ast
from orccad_app.lang.run_args import is_constant

__all__ = ["evaluate", "call_form", "task_arguments"]

_OPS = {"+": operator.add, "-": operator.sub, "*": operator.mul, "/": operator.truediv,
        "<": operator.lt, "<=": operator.le, ">": operator.gt, ">=": operator.ge,
        "==": operator.eq, "!=": operator.ne}


def _vector_op(op, left, right):
    if isinstance(left, list) or isinstance(right, list):
        size = len(left) if isinstance(left, list) else len(right)
        lhs = left if isinstance(left, list) else [left] * size
        rhs = right if isinstance(right, list) else [right] * size
        if len(lhs) != len(rhs):
            raise ValueError(f"vectors of sizes {len(lhs)} and {len(rhs)}")
        return [op(a, b) for a, b in zip(lhs, rhs)]
    return op(left, right)


def evaluate(expr: ast.Expr, env: Mapping[str, Any]) -> Any:
    """The value of ``expr`` where names are the Robot-Task's parameters in ``env``."""
    if isinstance(expr, (ast.Number, ast.String, ast.Bool)):
        return expr.value
    if isinstance(expr, ast.DurationLit):
        return expr.duration_ns
    if isinstance(expr, ast.Vector):
        return [evaluate(item, env) for item in expr.items]
    if isinstance(expr, ast.Name):
        if expr.name not in env:
            known = ", ".join(env) or "none"
            raise OrccadError(f"unknown name '{expr.name}' (the task's parameters: {known})",
                              expr.loc)
        return env[expr.name]
    if isinstance(expr, ast.Call):
        return call_form(expr, env)
    try:
        if isinstance(expr, ast.Unary):
            value = evaluate(expr.operand, env)
            if expr.op == "-":
                return [-v for v in value] if isinstance(value, list) else -value
            return not value
        if isinstance(expr, ast.Binary):
            left, right = evaluate(expr.left, env), evaluate(expr.right, env)
            if expr.op in ("and", "or"):
                return (left and right) if expr.op == "and" else (left or right)
            return _vector_op(_OPS[expr.op], left, right)
    except (TypeError, ValueError, ZeroDivisionError) as error:
        raise OrccadError(f"cannot compute this value: {error}", expr.loc) from None
    raise OrccadError("this expression is not a value of a Robot-Task clause", expr.loc)


def call_form(call: ast.Call, env: Mapping[str, Any]) -> tuple[str, dict[str, Any]]:
    """``name(a = 1, b = f(c = 2))`` as ``("name", {"a": 1, "b": ("f", {"c": 2})})``."""
    args: dict[str, Any] = {}
    for arg in call.args:
        if arg.name is None:
            raise OrccadError(f"arguments of '{call.func}' must be named (name = value)",
                              arg.loc)
        if arg.name in args:
            raise OrccadError(f"argument '{arg.name}' of '{call.func}' is given twice", arg.loc)
        args[arg.name] = evaluate(arg.value, env)
    return call.func, args


def _check_type(param: ast.Param, value: Any, loc) -> Any:
    kind = param.type
    ok = {
        None: True,
        "float": isinstance(value, (int, float)) and not isinstance(value, bool),
        "int": isinstance(value, int) and not isinstance(value, bool),
        "bool": isinstance(value, bool),
        "string": isinstance(value, str),
        "vector": isinstance(value, list) and all(isinstance(v, (int, float)) for v in value),
        "duration": isinstance(value, int) and not isinstance(value, bool),
    }.get(kind, True)
    if not ok:
        raise OrccadError(f"parameter '{param.name}' is a {kind}, got {value!r}", loc)
    return float(value) if kind == "float" else value


def task_arguments(task: ast.RobotTask, args: tuple[ast.Arg, ...] = (),
                   caller_env: Mapping[str, Any] | None = None,
                   actual: Mapping[str, Any] | None = None) -> dict[str, Any]:
    """The task's parameters bound for one ``run``: defaults, then the given arguments.

    A run-time argument (one that reads a variable or a signal value, see
    :mod:`orccad_app.lang.run_args`) takes its value from ``actual`` (the values computed when
    the task starts, already checked) and, without one, the parameter's default: the
    *nominal* binding the compiler checks the control scheme with.
    """
    bound: dict[str, Any] = {}
    given: dict[str, ast.Arg] = {}
    for index, written in enumerate(args):
        if written.name is None:
            if index >= len(task.params):
                raise OrccadError(f"too many arguments for Robot-Task '{task.name}'",
                                  written.loc)
            given[task.params[index].name] = written
        else:
            given[written.name] = written
    for param in task.params:
        arg: ast.Arg | None = given.pop(param.name, None)
        if arg is not None and not is_constant(arg.value):
            if actual is not None and param.name in actual:
                bound[param.name] = actual[param.name]
                continue
            arg = None  # the nominal binding: the default (the checker requires one)
        if arg is not None:
            value = evaluate(arg.value, caller_env or {})
            bound[param.name] = _check_type(param, value, arg.loc)
        elif param.default is not None:
            bound[param.name] = _check_type(param, evaluate(param.default, bound), param.loc)
        else:
            raise OrccadError(f"Robot-Task '{task.name}' needs a value for parameter "
                              f"'{param.name}'", param.loc)
    for name, arg in given.items():
        raise OrccadError(f"Robot-Task '{task.name}' has no parameter '{name}'", arg.loc)
    return bound
