"""The properties ``orccad check`` proves on every mission, whatever its ``property`` lines.

``fatal-aborts``
    In the instant a type-3 exception is raised (a task's fatal event while it runs), the
    mission's status is ``aborted`` and no Robot-Task is active after the instant, except
    those that the ``on fatal`` block starts.
``one-task-per-robot``
    No reachable state has two Robot-Task instances active on the same robot.
``no-deadlock``
    From every reachable state, an end (the terminated mission) or an *intended endless*
    state stays reachable. A state is intended endless when one of its pauses, or the
    ``run`` of one of its active Robot-Tasks, lies inside a ``halt``, a ``sustain``, a
    ``loop`` (with or without ``each``) or an ``every`` of the mission: those never end by
    design. A state that can reach neither is stuck (e.g. ``await`` of a local signal that
    nothing emits, a Robot-Task waiting for a pre-condition the mission never emits).
``tasks-end-first``
    In the instant the mission ends (``done``, ``failed``, ``aborted``, or the end of its
    ``on fatal`` block), every Robot-Task it started has ended or is killed: none is active
    after the instant, except, when it is aborted, those of ``on fatal``.

Each check is a graph search of the model; a violation comes with the shortest run to it.
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass
from typing import Callable

import networkx as nx

from orccad_app.lang import ast
from orccad_app.reactive.status import Status
from orccad_app.robottask.application import contains
from orccad_app.verify.model import ENDED, Model, Step

__all__ = ["Violation", "BUILTINS", "check_builtin", "shortest_run"]

BUILTINS = ("fatal-aborts", "one-task-per-robot", "no-deadlock", "tasks-end-first")


@dataclass(frozen=True)
class Violation:
    """Why a built-in property fails, and the run (model steps from the start) showing it."""

    message: str
    steps: tuple[Step, ...]


def shortest_run(model: Model, goal: Callable[[Step], bool]) -> tuple[Step, ...] | None:
    """The shortest run from the initial state whose last step satisfies ``goal``."""
    parent: dict[int, Step | None] = {0: None}
    queue = deque([0])
    while queue:
        state = queue.popleft()
        for step in model.steps[state]:
            if goal(step):
                run = [step]
                while parent[run[-1].source] is not None:
                    run.append(parent[run[-1].source])  # type: ignore[arg-type]
                return tuple(reversed(run))
            if step.target not in parent:
                parent[step.target] = step
                queue.append(step.target)
    return None


def _fatal_sites(model: Model) -> frozenset[int]:
    return frozenset(s.number for s in model.composition.sites if s.on_fatal)


def _raises_fatal(model: Model, step: Step) -> str | None:
    if step.path is None:
        return None
    guard = dict(step.path.guard)
    for task in model.composition.program.robottasks:
        for exc in task.exceptions:
            if exc.type is ast.ExceptionType.FATAL and guard.get(f"{task.name}.{exc.name}") \
                    and f"{exc.name}.raised" in step.emitted:
                return exc.name
    return None


def _fatal_aborts(model: Model) -> Violation | None:
    allowed = _fatal_sites(model)

    def bad(step: Step) -> bool:
        if _raises_fatal(model, step) is None:
            return False
        return step.status != Status.ABORTED or not model.sites(step.target) <= allowed

    run = shortest_run(model, bad)
    if run is None:
        return None
    name = _raises_fatal(model, run[-1])
    still = sorted(model.active_tasks(run[-1].target))
    return Violation(f"type-3 exception {name} gives status {run[-1].status}"
                     + (f" with {', '.join(still)} still active" if still else ""), run)


def _one_task_per_robot(model: Model) -> Violation | None:
    robot = {s.number: (s.robot, s.task) for s in model.composition.sites}

    def clash(state: int) -> tuple | None:
        seen: dict[str, str] = {}
        for site in sorted(model.sites(state)):
            name, task = robot[site]
            if name in seen:
                return name, seen[name], task
            seen[name] = task
        return None

    run = shortest_run(model, lambda step: clash(step.target) is not None)
    if run is None:
        return None
    name, first, second = clash(run[-1].target)  # type: ignore[misc]
    return Violation(f"{first} and {second} are active at once on robot {name}", run)


def _endless_spans(mission: ast.Mission, program: ast.Program) -> list:
    """The spans of the statements meant to run forever, in the mission and the
    sub-missions it runs (imported ones included)."""
    spans = []
    stack: list = [mission.body] + ([mission.on_fatal] if mission.on_fatal else [])
    entered = {mission.name}
    while stack:
        node = stack.pop()
        if isinstance(node, (ast.Halt, ast.Sustain, ast.Loop, ast.Every)):
            spans.append(node.loc)
        if isinstance(node, ast.RunMission) and node.mission not in entered:
            entered.add(node.mission)
            target = program.mission(node.mission)
            if target is not None:
                stack.append(target.body)
        if isinstance(node, tuple):
            stack.extend(node)
        elif hasattr(node, "__dataclass_fields__"):
            stack.extend(getattr(node, f) for f in node.__dataclass_fields__)
    return spans


def _no_deadlock(model: Model) -> Violation | None:
    spans = _endless_spans(model.composition.mission, model.composition.program)
    run_loc = {s.number: s.loc for s in model.composition.sites}
    automaton = model.automaton

    def intended(state: int) -> bool:
        q = model.control(state)
        places = list(automaton.waiting[q]) + [run_loc[s] for s in model.sites(state)]
        return any(contains(span, place) for span in spans for place in places)

    good = {s for s in range(len(model.states)) if model.is_end(s) or intended(s)}
    predecessors: dict[int, list[int]] = {}
    for steps in model.steps:
        for step in steps:
            predecessors.setdefault(step.target, []).append(step.source)
    queue = deque(good)
    while queue:
        state = queue.popleft()
        for source in predecessors.get(state, ()):
            if source not in good:
                good.add(source)
                queue.append(source)
    if len(good) == len(model.states):
        return None
    stuck = _stuck_states(model, good)
    run = () if 0 in stuck else shortest_run(model, lambda step: step.target in stuck)
    state = run[-1].target if run else 0
    where = ", ".join(str(loc) for loc in automaton.waiting[model.control(state)]) \
        or "its start"
    return Violation(f"the mission can get stuck waiting at {where}: no end is reachable "
                     "from there and no loop or halt is meant to run forever", tuple(run))


def _stuck_states(model: Model, good: set[int]) -> set[int]:
    """States of the bottom strongly connected components that hold no good state (where
    the mission stays forever once there)."""
    graph = nx.DiGraph()
    graph.add_nodes_from(range(len(model.states)))
    graph.add_edges_from((s.source, s.target) for steps in model.steps for s in steps)
    condensed = nx.condensation(graph)
    stuck: set[int] = set()
    for component in condensed.nodes:
        members = condensed.nodes[component]["members"]
        if condensed.out_degree(component) == 0 and not members & good:
            stuck |= members
    return stuck


def _tasks_end_first(model: Model) -> Violation | None:
    allowed = _fatal_sites(model)

    def bad(step: Step) -> bool:
        if step.status not in (Status.DONE, Status.FAILED, Status.ABORTED, ENDED):
            return False
        left = model.sites(step.target)
        return bool(left - allowed) if step.status == Status.ABORTED else bool(left)

    run = shortest_run(model, bad)
    if run is None:
        return None
    still = ", ".join(sorted(model.active_tasks(run[-1].target)))
    return Violation(f"the mission ends ({run[-1].status}) with {still} still active", run)


_CHECKS = {"fatal-aborts": _fatal_aborts, "one-task-per-robot": _one_task_per_robot,
           "no-deadlock": _no_deadlock, "tasks-end-first": _tasks_end_first}


def check_builtin(model: Model, name: str) -> Violation | None:
    """None when built-in property ``name`` holds, else the violation."""
    return _CHECKS[name](model)
