"""Resource conflicts: two Robot-Tasks on one robot must never run in parallel.

A Robot-Task uses a fixed set of physical resources (its robot, RR-1801 §3). Two ``run``
statements on the same robot in different branches of one ``par`` or ``race`` could be
active in the same instant; the compiler rejects that, naming both tasks and the robot.
"""

from __future__ import annotations

from orccad_app.diagnostics import Diagnostic, OrccadError
from orccad_app.lang import ast
from orccad_app.lang.walk import nodes, runs

__all__ = ["check_resources"]


def _check(block, robot_of: dict[str, str]) -> None:
    for node in nodes(block):
        if not isinstance(node, (ast.Par, ast.Race)):
            continue
        seen: dict[str, ast.Run] = {}  # robot -> a run of an earlier branch
        for branch in node.branches:
            mine: dict[str, ast.Run] = {}
            for run in runs(branch):
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


def check_resources(program: ast.Program, mission: ast.Mission) -> None:
    """Raise :class:`OrccadError` if two ``run`` on one robot may be active at once."""
    robot_of = {task.name: task.robot for task in program.robottasks}
    _check(mission.body, robot_of)
    if mission.on_fatal is not None:
        _check(mission.on_fatal, robot_of)
