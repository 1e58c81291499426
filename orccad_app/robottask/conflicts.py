"""Resource conflicts: two Robot-Tasks on one robot must never run in parallel.

A Robot-Task uses a fixed set of physical resources (its robot, RR-1801 §3). Two ``run``
statements on the same robot in different branches of one ``par`` or ``race`` could be
active in the same instant; the compiler rejects that, naming both tasks and the robot.
"""

from __future__ import annotations

from typing import Iterator

from orccad_app.diagnostics import Diagnostic, OrccadError
from orccad_app.lang import ast

__all__ = ["check_resources"]


def _children(node) -> Iterator:
    for name in getattr(node, "__dataclass_fields__", ()):
        value = getattr(node, name)
        for item in value if isinstance(value, tuple) else (value,):
            if isinstance(item, (ast.Block, ast.Catch)) or type(item).__name__ in _STATEMENTS:
                yield item


_STATEMENTS = {cls.__name__ for cls in (
    ast.Nothing, ast.Pause, ast.Halt, ast.Emit, ast.Sustain, ast.Await, ast.Run, ast.If,
    ast.Loop, ast.Repeat, ast.Every, ast.Abort, ast.Suspend, ast.Trap, ast.Exit, ast.Try,
    ast.Par, ast.Race, ast.LocalSignals, ast.VarDecl, ast.Assign)}


def _runs(node) -> Iterator[ast.Run]:
    if isinstance(node, ast.Run):
        yield node
    for child in _children(node):
        yield from _runs(child)


def _check(node, robot_of: dict[str, str]) -> None:
    if isinstance(node, (ast.Par, ast.Race)):
        seen: dict[str, ast.Run] = {}  # robot -> a run of an earlier branch
        for branch in node.branches:
            mine: dict[str, ast.Run] = {}
            for run in _runs(branch):
                robot = robot_of.get(run.task)
                if robot is None:
                    continue
                other = seen.get(robot)
                if other is not None:
                    raise OrccadError(
                        f"resource conflict: Robot-Tasks {other.task} and {run.task} both use "
                        f"robot '{robot}' and may run in parallel branches",
                        run.task_loc or run.loc,
                        (Diagnostic("note", f"{other.task} runs here", other.loc),))
                mine.setdefault(robot, run)
            for robot, run in mine.items():
                seen.setdefault(robot, run)
    for child in _children(node):
        _check(child, robot_of)


def check_resources(program: ast.Program, mission: ast.Mission) -> None:
    """Raise :class:`OrccadError` if two ``run`` on one robot may be active at once."""
    robot_of = {task.name: task.robot for task in program.robottasks}
    _check(mission.body, robot_of)
    if mission.on_fatal is not None:
        _check(mission.on_fatal, robot_of)
