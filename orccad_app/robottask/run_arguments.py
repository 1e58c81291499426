"""The run-time arguments of a ``run`` site, as the lowering exposes them.

``run GoTo(target = ?Waypoint)``: the argument reads a signal value, so it is evaluated in the
instant the task starts (:mod:`orccad_app.lang.run_args`). The lowering emits, in that very
instant, the hidden valued output ``GoTo.arg.target`` carrying the value (one output per
Robot-Task and parameter, role :attr:`~orccad_app.robottask.signals.RoleKind.ARGUMENT`); the
mission layer reads it when it starts the task's modules and binds the task with it
(:mod:`orccad_app.robottask.binding`). ``orccad react`` shows it like any output.
"""

from __future__ import annotations

from dataclasses import dataclass

from orccad_app.diagnostics import SourceLocation
from orccad_app.lang import ast
from orccad_app.lang.run_args import is_constant, param_type

__all__ = ["RunArgument", "runtime_arguments", "argument_signal", "argument_type"]


@dataclass(frozen=True)
class RunArgument:
    """One run-time argument of a run site.

    :param param: the Robot-Task parameter it gives.
    :param expr: its expression (evaluated when the task starts).
    :param loc: the argument's location (``param = expr``): where a bad value is reported.
    :param signal: the automaton output carrying its value in the instant the task starts.
    """

    param: str
    expr: ast.Expr
    loc: SourceLocation
    signal: str


def argument_signal(task: str, param: str) -> str:
    """The name of the output carrying parameter ``param`` of ``task`` at its start."""
    return f"{task}.arg.{param}"


def argument_type(param: ast.Param) -> str:
    """The value type of the output carrying ``param`` (the parameter's, else its default's;
    ``float`` when neither says)."""
    return param_type(param).type or "float"


def runtime_arguments(task: ast.RobotTask, run: ast.Run) -> tuple[tuple[ast.Param, ast.Arg], ...]:
    """The arguments of ``run`` that are not compile-time constants, with their parameters
    (positional arguments resolved), in parameter order; unknown names are left out (the
    checker reports them)."""
    given: dict[str, ast.Arg] = {}
    for index, arg in enumerate(run.args):
        name = arg.name if arg.name is not None else (
            task.params[index].name if index < len(task.params) else None)
        if name is not None and not is_constant(arg.value):
            given.setdefault(name, arg)
    return tuple((p, given[p.name]) for p in task.params if p.name in given)
