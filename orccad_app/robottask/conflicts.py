"""Resource conflicts: two Robot-Tasks on one robot must never run in parallel.

A Robot-Task uses a fixed set of physical resources (its robot, RR-1801 §3). Two ``run``
statements on the same robot in different branches of one ``par`` or ``race`` could be
active in the same instant; the compiler rejects that, naming both tasks and the robot. The
``run`` statements of a branch include those of the sub-missions it runs (``run mission``,
transitively), and the sub-missions' own bodies are checked too.
"""

from __future__ import annotations

from orccad_app.diagnostics import Diagnostic, OrccadError
from orccad_app.lang import ast
from orccad_app.lang.walk import nodes

__all__ = ["check_resources"]


def _runs(node, program: ast.Program, entered: frozenset[str]):
    """``(run, call)`` for every ``run`` in ``node`` and in the sub-missions it runs;
    ``call`` is the ``run mission`` statement of ``node`` that leads to it (None: direct)."""
    for item in nodes(node):
        if isinstance(item, ast.Run):
            yield item, None
        elif isinstance(item, ast.RunMission) and item.mission not in entered:
            target = program.mission(item.mission)
            if target is not None:
                for run, _ in _runs(target.body, program, entered | {item.mission}):
                    yield run, item


def _conflict(robot: str, first: tuple, second: tuple) -> OrccadError:
    (other, other_call), (run, call) = first, second
    notes = [Diagnostic("note", f"{other.task} runs here", other.loc)]
    if other_call is not None:
        notes.append(Diagnostic("note", f"in sub-mission '{other_call.mission}' run here",
                                other_call.loc))
    if call is not None:
        notes.append(Diagnostic("note", f"{run.task} runs here", run.loc))
    return OrccadError(
        f"resource conflict: Robot-Tasks {other.task} and {run.task} both use robot "
        f"'{robot}' and may run in parallel branches"
        + (f" ({run.task} in sub-mission '{call.mission}')" if call is not None else ""),
        call.loc if call is not None else run.task_loc or run.loc, tuple(notes))


def _check(block, robot_of: dict[str, str], program: ast.Program,
           entered: frozenset[str]) -> None:
    for node in nodes(block):
        if not isinstance(node, (ast.Par, ast.Race)):
            continue
        seen: dict[str, tuple] = {}  # robot -> (run, call) of an earlier branch
        for branch in node.branches:
            mine: dict[str, tuple] = {}
            for run, call in _runs(branch, program, entered):
                robot = robot_of.get(run.task)
                if robot is None:
                    continue
                other = seen.get(robot)
                if other is not None:
                    raise _conflict(robot, other, (run, call))
                mine.setdefault(robot, (run, call))
            for robot, found in mine.items():
                seen.setdefault(robot, found)


def check_resources(program: ast.Program, mission: ast.Mission) -> None:
    """Raise :class:`OrccadError` if two ``run`` on one robot may be active at once."""
    robot_of = {task.name: task.robot for task in program.robottasks}
    entered = frozenset({mission.name})
    blocks = [mission.body] + ([mission.on_fatal] if mission.on_fatal is not None else [])
    for block in blocks:
        _check(block, robot_of, program, entered)
    checked = set(entered)
    stack = [n.mission for b in blocks for n in nodes(b) if isinstance(n, ast.RunMission)]
    while stack:  # the sub-missions' own bodies
        name = stack.pop()
        target = program.mission(name)
        if name in checked or target is None:
            continue
        checked.add(name)
        _check(target.body, robot_of, program, frozenset(checked))
        stack += [n.mission for n in nodes(target.body) if isinstance(n, ast.RunMission)]
