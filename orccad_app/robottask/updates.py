"""Type-1 updates that compute (RR-1801 §3.4.2): the value of ``adjust m.p = VALUE``.

``VALUE`` is either an expression or a ramp:

- an **expression** over numbers, the Robot-Task's parameters, the *current* values of
  Module-Task parameters of the same task (``ctrl.kp``), ``+ - * /``, unary ``-``, vectors
  ``[…]`` and the functions ``min(a, b, …)``, ``max(a, b, …)``, ``abs(x)`` and
  ``clip(x, lo, hi)`` (element-wise on vectors): ``min(ctrl.kp * 1.5, 800.0)``;
- a **ramp** ``ramp(START, END, DURATION)`` (named: ``start =``, ``end =``, ``duration =``):
  the parameter goes from ``START`` to ``END`` linearly over ``DURATION`` (a duration literal,
  ``2 s``), set at every release of the module; ``START`` and ``END`` are expressions as above,
  computed when the update is applied.

:func:`update_form` checks the shape of ``VALUE`` when the Robot-Task is instantiated;
:func:`compute` evaluates an expression given how to read a module parameter. A value is a
``float`` or a read-only ``numpy`` vector; a non-finite result is left to the parameter's check
(the caller's), which refuses it.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable, Mapping

import numpy as np

from orccad_app.diagnostics import OrccadError
from orccad_app.lang import ast

__all__ = ["Ramp", "UpdateForm", "FUNCTIONS", "update_form", "compute", "param_reads"]

#: ``read(module, param)``: the current value of a Module-Task parameter of the task.
Reader = Callable[[str, str], Any]

#: name -> (minimum, maximum number of arguments) of the functions of an update expression.
FUNCTIONS: dict[str, tuple[int, int | None]] = {"min": (2, None), "max": (2, None),
                                                 "abs": (1, 1), "clip": (3, 3)}
_RAMP_ARGS = ("start", "end", "duration")


@dataclass(frozen=True)
class Ramp:
    """``ramp(start, end, duration)``: a gradual change over ``duration_ns`` [ns]."""

    start: ast.Expr
    end: ast.Expr
    duration_ns: int


@dataclass(frozen=True)
class UpdateForm:
    """The checked value of an ``adjust``: an expression, or a :class:`Ramp`.

    :param expr: the new value's expression (``None`` for a ramp).
    :param ramp: the ramp (``None`` for an expression).
    :param reads: the module parameters it reads, ``(module, param)`` in source order.
    """

    expr: ast.Expr | None
    ramp: Ramp | None
    reads: tuple[ast.ParamRef, ...]

    @property
    def constant(self) -> bool:
        """It reads no module parameter: its value is known when the task is instantiated."""
        return not self.reads

    @property
    def expressions(self) -> tuple[ast.Expr, ...]:
        """The expression, or the ramp's start and end."""
        if self.ramp is not None:
            return (self.ramp.start, self.ramp.end)
        assert self.expr is not None
        return (self.expr,)


def param_reads(expr: ast.Expr) -> tuple[ast.ParamRef, ...]:
    """The ``module.param`` references of ``expr``, in source order."""
    if isinstance(expr, ast.ParamRef):
        return (expr,)
    if isinstance(expr, ast.Unary):
        return param_reads(expr.operand)
    if isinstance(expr, ast.Binary):
        return param_reads(expr.left) + param_reads(expr.right)
    if isinstance(expr, ast.Vector):
        return tuple(r for item in expr.items for r in param_reads(item))
    if isinstance(expr, ast.Call):
        return tuple(r for arg in expr.args for r in param_reads(arg.value))
    return ()


def _ramp(call: ast.Call) -> Ramp:
    given: dict[str, ast.Arg] = {}
    for index, arg in enumerate(call.args):
        name = arg.name if arg.name is not None else (
            _RAMP_ARGS[index] if index < len(_RAMP_ARGS) else None)
        if name not in _RAMP_ARGS or name in given:
            raise OrccadError("ramp takes (start, end, duration): e.g. ramp(0.0, 1.0, 2 s)",
                              arg.loc)
        given[name] = arg
    missing = [name for name in _RAMP_ARGS if name not in given]
    if missing:
        raise OrccadError(f"ramp needs {', '.join(missing)}: ramp(start, end, duration), "
                          "e.g. ramp(0.0, 1.0, 2 s)", call.loc)
    duration = given["duration"].value
    if not isinstance(duration, ast.DurationLit) or duration.duration_ns <= 0:
        raise OrccadError("the duration of a ramp is a duration literal > 0 (2 s, 500 ms)",
                          given["duration"].loc)
    for name in ("start", "end"):
        _check(given[name].value)
    return Ramp(given["start"].value, given["end"].value, duration.duration_ns)


def _refused(expr: Any) -> str:
    if isinstance(expr, (ast.Unary, ast.Binary)):
        return f"'{expr.op}'"
    if isinstance(expr, (ast.LastValue, ast.PreValue, ast.PreSignal)):
        return "signals"
    if isinstance(expr, ast.DurationLit):
        return "durations (only a ramp's third argument is one)"
    return "strings or booleans (only as the whole value: adjust m.p = false)"


def _check(expr: ast.Expr) -> None:
    """Refuse what an update expression cannot compute, with its location."""
    if isinstance(expr, (ast.Number, ast.Name, ast.ParamRef)):
        return
    if isinstance(expr, ast.Vector):
        for item in expr.items:
            _check(item)
        return
    if isinstance(expr, ast.Unary) and expr.op == "-":
        _check(expr.operand)
        return
    if isinstance(expr, ast.Binary) and expr.op in "+-*/":
        _check(expr.left)
        _check(expr.right)
        return
    if isinstance(expr, ast.Call):
        _check_call(expr)
        return
    raise OrccadError("a type-1 update computes with numbers, vectors, the task's parameters, "
                      "module parameters (ctrl.kp), + - * / and min, max, abs, clip; not "
                      f"with {_refused(expr)}", getattr(expr, "loc", None))


def _check_call(call: ast.Call) -> None:
    if call.func == "ramp":
        raise OrccadError("ramp(…) is the whole value of an update, not part of an expression",
                          call.loc)
    arity = FUNCTIONS.get(call.func)
    if arity is None:
        raise OrccadError(f"unknown function '{call.func}' in a type-1 update (functions: "
                          f"{', '.join(FUNCTIONS)}, and ramp(start, end, duration))", call.loc)
    low, high = arity
    if len(call.args) < low or (high is not None and len(call.args) > high):
        count = str(low) if low == high else f"at least {low}"
        raise OrccadError(f"{call.func} takes {count} arguments, got {len(call.args)}",
                          call.loc)
    for arg in call.args:
        if arg.name is not None:
            raise OrccadError(f"the arguments of {call.func} are positional", arg.loc)
        _check(arg.value)
    if call.func == "clip":
        low_value, high_value = _literal(call.args[1].value), _literal(call.args[2].value)
        if low_value is not None and high_value is not None and low_value > high_value:
            raise OrccadError(_clip_bounds(low_value, high_value), call.loc)


def _literal(expr: ast.Expr) -> float | None:
    """The value of a number literal, or of a negated one; else ``None``."""
    if isinstance(expr, ast.Number):
        return float(expr.value)
    if isinstance(expr, ast.Unary) and expr.op == "-" and isinstance(expr.operand, ast.Number):
        return -float(expr.operand.value)
    return None


def _clip_bounds(low: Any, high: Any) -> str:
    return (f"clip(x, lo, hi) needs lo <= hi (got lo = {low}, hi = {high}): a clip with its "
            "bounds swapped would silently give hi")


def update_form(value: ast.Expr) -> UpdateForm:
    """The checked form of an ``adjust`` value (raises :class:`OrccadError`, located)."""
    if isinstance(value, ast.Call) and value.func == "ramp":
        ramp = _ramp(value)
        return UpdateForm(None, ramp, param_reads(ramp.start) + param_reads(ramp.end))
    if not isinstance(value, (ast.Bool, ast.String)):  # a literal is a whole value
        _check(value)
    return UpdateForm(value, None, param_reads(value))


def _plain(value: Any) -> Any:
    array = np.asarray(value, dtype=float)
    return float(array) if array.ndim == 0 else array


def _call(call: ast.Call, args: list[Any]) -> Any:
    with np.errstate(all="ignore"):
        if call.func == "min":
            return _plain(np.minimum.reduce(np.broadcast_arrays(*args)))
        if call.func == "max":
            return _plain(np.maximum.reduce(np.broadcast_arrays(*args)))
        if call.func == "abs":
            return _plain(np.abs(args[0]))
        if np.any(np.asarray(args[1]) > np.asarray(args[2])):
            raise OrccadError(_clip_bounds(_plain(args[1]), _plain(args[2])), call.loc)
        return _plain(np.minimum(np.maximum(args[0], args[1]), args[2]))


def _number(value: Any, loc: Any) -> Any:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.ndarray, list)):
        raise OrccadError(f"a type-1 update computes with numbers, got {value!r}", loc)
    try:
        return _plain(value)
    except (TypeError, ValueError):
        raise OrccadError(f"a type-1 update computes with numbers, got {value!r}", loc) from None


def compute(expr: ast.Expr, env: Mapping[str, Any], read: Reader) -> Any:
    """The value of the update expression ``expr`` (checked by :func:`update_form`): names
    are the task's parameters in ``env``, ``m.p`` is ``read(m, p)``."""
    if isinstance(expr, (ast.Bool, ast.String)):
        return expr.value
    if isinstance(expr, ast.Number):
        return float(expr.value)
    if isinstance(expr, ast.Name):
        value = env[expr.name]
        return _plain(value) if isinstance(value, list) else value
    if isinstance(expr, ast.ParamRef):
        try:
            return read(expr.module, expr.param)
        except OrccadError as error:
            if error.location is None:
                raise OrccadError(error.message, expr.loc) from None
            raise
    if isinstance(expr, ast.Vector):
        items = [_operand(item, env, read) for item in expr.items]
        if any(np.ndim(item) for item in items):
            raise OrccadError("the items of a vector are numbers, got a vector", expr.loc)
        return _plain(items)
    if isinstance(expr, ast.Unary):
        return _plain(-np.asarray(_operand(expr.operand, env, read)))
    if isinstance(expr, ast.Binary):
        left, right = _operand(expr.left, env, read), _operand(expr.right, env, read)
        try:
            with np.errstate(all="ignore"):
                a, b = np.asarray(left), np.asarray(right)
                result = {"+": np.add, "-": np.subtract, "*": np.multiply,
                          "/": np.divide}[expr.op](a, b)
        except ValueError as error:
            raise OrccadError(f"cannot compute this value: {error}", expr.loc) from None
        return _plain(result)
    if isinstance(expr, ast.Call):
        args = [_operand(arg.value, env, read) for arg in expr.args]
        try:
            return _call(expr, args)
        except ValueError as error:
            raise OrccadError(f"cannot compute this value: {error}", expr.loc) from None
    raise OrccadError("not a value of a type-1 update", getattr(expr, "loc", None))


def _operand(expr: ast.Expr, env: Mapping[str, Any], read: Reader) -> Any:
    """An operand of arithmetic or of a function: a number or a vector of numbers."""
    return _number(compute(expr, env, read), getattr(expr, "loc", None))
