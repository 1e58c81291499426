"""Binding a Robot-Task's run-time arguments when it starts.

The compiler checked the task's control scheme with the *nominal* binding (each run-time
argument replaced by its parameter's default, :func:`~orccad_app.robottask.values.task_arguments`).
When the task starts, :func:`bind_arguments` checks the actual values and instantiates the task
with them, with every check the compiler runs on constants:

1. each value against its parameter: its type (an ``int`` fits a ``float``), finite numbers, a
   vector of the size of the parameter's default;
2. the control scheme with these values (:func:`~orccad_app.robottask.model.instantiate`): the
   ranges the module kinds, the task function and the law declare, their coherence;
3. the same Module-Tasks, ports and dimensions as the nominal scheme (the TCS is built before
   the run).

A refused value raises :class:`ArgumentError`, located at the argument in the mission
(``file:line:col``), with a note at the Robot-Task clause that refused it: the mission run
ends ``failed`` with that reason. Nothing is clamped or converted silently.
"""

from __future__ import annotations

import math
from typing import Any, Mapping

from orccad_app.diagnostics import Diagnostic, OrccadError, value_excerpt
from orccad_app.lang import ast
from orccad_app.lang.run_args import param_type
from orccad_app.robottask.model import RobotTaskInstance, instantiate
from orccad_app.robottask.run_arguments import RunArgument

__all__ = ["ArgumentError", "bind_arguments", "check_value", "plain_arguments"]


class ArgumentError(OrccadError):
    """A run-time argument's value is refused when its Robot-Task starts."""


def _real(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _vector(param: ast.Param, value: Any, nominal: Any) -> list[float]:
    if not isinstance(value, (list, tuple)) or not all(_real(v) for v in value):
        raise ValueError(f"a vector of numbers is expected, got {value_excerpt(value)}")
    items = [float(v) for v in value]
    if not all(math.isfinite(v) for v in items):
        raise ValueError(f"every component must be a finite number, got {value_excerpt(value)}")
    size = len(nominal) if isinstance(nominal, (list, tuple)) else None
    if size is not None and len(items) != size:
        raise ValueError(f"a vector of {size} components is expected (the size of the "
                         f"default of '{param.name}'), got {len(items)}: {value_excerpt(value)}")
    return items


def check_value(param: ast.Param, value: Any, nominal: Any) -> Any:
    """``value`` as parameter ``param`` takes it (``nominal``: its default's value); raises
    :class:`ValueError` saying why it does not fit."""
    kind = param_type(param).type
    if kind == "vector":
        return _vector(param, value, nominal)
    if kind in ("float", "int", "duration"):
        if not _real(value) or (kind != "float" and not isinstance(value, int)):
            raise ValueError(f"{'an integer' if kind != 'float' else 'a number'} is expected, "
                             f"got {value_excerpt(value)}")
        if not math.isfinite(value):
            raise ValueError(f"a finite number is expected, got {value_excerpt(value)}")
        if kind == "duration" and value < 0:
            raise ValueError(f"a duration must be >= 0, got {value}")
        return float(value) if kind == "float" else value
    if kind == "bool" and not isinstance(value, bool):
        raise ValueError(f"true or false is expected, got {value_excerpt(value)}")
    if kind == "string" and not isinstance(value, str):
        raise ValueError(f"a string is expected, got {value_excerpt(value)}")
    return value


def plain_arguments(params: Mapping[str, Any]) -> dict[str, Any]:
    """The task's parameter values as JSON-able data (vectors as lists)."""
    def plain(value: Any) -> Any:
        if hasattr(value, "tolist"):
            return value.tolist()
        if isinstance(value, (list, tuple)):
            return [plain(v) for v in value]
        return value
    return {name: plain(value) for name, value in params.items()}


def _refused(task: str, arg: RunArgument, value: Any, why: str,
             notes: tuple[Diagnostic, ...] = ()) -> ArgumentError:
    return ArgumentError(f"run-time argument of {task}: {arg.param} = {value_excerpt(value)} is "
                         f"refused when the task starts: {why}", arg.loc, notes)


def _scheme(instance: RobotTaskInstance) -> dict[str, tuple]:
    return {name: (spec.kind.name, tuple((p.name, p.direction, p.type, p.dim)
                                         for p in spec.instance.ports))
            for name, spec in instance.modules.items()}


def _instantiate(nominal: RobotTaskInstance, actual: dict[str, Any]) -> RobotTaskInstance:
    return instantiate(nominal.task, nominal.robots, nominal.host, nominal.args,
                       nominal.run_loc, actual)


def _culprit(nominal: RobotTaskInstance, arguments: tuple[RunArgument, ...],
             actual: dict[str, Any]) -> RunArgument:
    """The first argument whose value, added to the previous ones, makes the scheme fail."""
    partial: dict[str, Any] = {}
    for arg in arguments:
        partial[arg.param] = actual[arg.param]
        try:
            _instantiate(nominal, partial)
        except OrccadError:
            return arg
    return arguments[-1]


def bind_arguments(nominal: RobotTaskInstance, arguments: tuple[RunArgument, ...],
                   values: Mapping[str, Any]) -> RobotTaskInstance:
    """The instance of a run site for the values of its run-time arguments (``values``:
    argument output -> value, as emitted in the instant the task starts)."""
    task = nominal.task
    actual: dict[str, Any] = {}
    for arg in arguments:
        value = values.get(arg.signal)
        param = task.param(arg.param)
        assert param is not None, arg
        try:
            actual[arg.param] = check_value(param, value, nominal.params.get(arg.param))
        except ValueError as error:
            raise _refused(task.name, arg, value, str(error)) from None
    try:
        bound = _instantiate(nominal, actual)
    except OrccadError as error:
        arg = _culprit(nominal, arguments, actual)
        notes: tuple[Diagnostic, ...] = error.notes
        if error.location is not None and error.location != arg.loc:
            notes = (Diagnostic("note", "refused by this clause of the Robot-Task",
                                error.location), *notes)
        raise _refused(task.name, arg, actual[arg.param], error.message, notes) from None
    before, after = _scheme(nominal), _scheme(bound)
    if before != after:
        changed = next(name for name in (*before, *after) if before.get(name) != after.get(name))
        raise _refused(task.name, arguments[0], actual[arguments[0].param],
                       f"the control scheme changes (module '{changed}': its kind or ports "
                       "differ from the scheme checked before the run)")
    return bound

