"""Observers of the motion: ``tracking_error(max)``, ``at_rest(tol)``, ``at_goal(tol)``."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from orccad_app.plugin_api import (
    REQUIRED,
    ControlError,
    ModuleContext,
    ParamSpec,
    TASK_ERROR,
    PortSpec,
    TaskFunction,
)

from orccad_observers.base import Monitor, ObserverKind
from orccad_observers.c_kinds import AT_REST_C, TRACKING_ERROR_C

__all__ = ["TrackingError", "AtRest", "AtGoal"]


def _norm(vector: Any) -> float:
    return float(np.max(np.abs(np.asarray(vector, dtype=float))))


class _TrackingErrorMonitor(Monitor):
    def __call__(self, t_s: float, inputs: Mapping[str, Any]) -> tuple[bool, float] | None:
        error = inputs.get(TASK_ERROR)
        if error is None:
            q, qd = inputs.get("q"), inputs.get("qd")
            if q is None or qd is None:
                return None
            error = np.asarray(q, dtype=float) - np.asarray(qd, dtype=float)
        value = _norm(error)
        return value > self.params["max"], value


class TrackingError(ObserverKind):
    """Fires when :math:`\\|e\\|_\\infty` exceeds ``max``; reads the task error ``e`` (the
    ``control_law``'s output) or, if unconnected, ``q - qd``. ``value`` is the norm."""

    name = "tracking_error"
    summary = "the task error's largest component exceeds max"
    inputs = (PortSpec(TASK_ERROR, "in", "vector", None, False, "task error e(q, t)"),
              PortSpec("q", "in", "vector", None, False, "joint positions [rad]"),
              PortSpec("qd", "in", "vector", None, False, "desired positions [rad]"))
    input_alternatives = (frozenset({TASK_ERROR}), frozenset({"q", "qd"}))
    own_params = (ParamSpec("max", "float", REQUIRED, "error bound [rad or m]", 0.0, True),)
    monitor = _TrackingErrorMonitor
    c_implementation = TRACKING_ERROR_C

    def input_dims(self, values: Mapping[str, Any], context: ModuleContext) -> dict[str, int]:
        dims = super().input_dims(values, context)
        if context.robot is not None and context.task_function is not None:
            dims[TASK_ERROR] = context.task_function.build(context.robot).dim
        else:
            dims.pop(TASK_ERROR, None)
        return dims


class _AtRestMonitor(Monitor):
    def __call__(self, t_s: float, inputs: Mapping[str, Any]) -> tuple[bool, float] | None:
        qdot = inputs.get("qdot")
        if qdot is None:
            return None
        value = _norm(qdot)
        return value <= self.params["tol"], value


class AtRest(ObserverKind):
    """Fires while every joint speed is at most ``tol`` [rad/s]; ``value`` is the largest."""

    name = "at_rest"
    summary = "every joint speed is within tol [rad/s]"
    inputs = (PortSpec("qdot", "in", "vector", None, True, "joint velocities [rad/s]"),)
    own_params = (ParamSpec("tol", "float", REQUIRED, "speed tolerance [rad/s]", 0.0, True),)
    monitor = _AtRestMonitor
    c_implementation = AT_REST_C


class _AtGoalMonitor(Monitor):
    def reset(self) -> None:
        context = self.context
        self.task: TaskFunction | None = None
        if context.task_function is not None and context.robot is not None:
            self.task = context.task_function.build(context.robot)
        self.goal: np.ndarray | None = None
        self.armed_at = 0.0

    def _resolve_goal(self, q: np.ndarray) -> None:
        if self.params["goal"] is not None:
            self.goal = np.asarray(self.params["goal"], dtype=float)
            return
        task = self.task
        task.start_from(q)
        trajectory = task.trajectory
        end = trajectory.end_time_s
        self.armed_at = self.context.duration_s if end is None else end
        final = trajectory.final()
        self.goal = final if final is not None else trajectory.sample(self.armed_at).pos

    def __call__(self, t_s: float, inputs: Mapping[str, Any]) -> tuple[bool, float] | None:
        q = inputs.get("q")
        if q is None:
            return None
        q = np.asarray(q, dtype=float)
        goal = inputs.get("goal")
        if goal is None and self.goal is None:
            self._resolve_goal(q)
        if goal is not None:
            value = _norm(q - np.asarray(goal, dtype=float))
        elif self.params["goal"] is not None:
            value = _norm(q - self.goal)
        else:  # the trajectory's final point, in the task function's space
            value = _norm(self.task.measure(q) - self.goal)
        holds = value <= self.params["tol"] and (goal is not None or t_s >= self.armed_at)
        qdot, vel_tol = inputs.get("qdot"), self.params["vel_tol"]
        if holds and qdot is not None and vel_tol is not None:
            holds = _norm(qdot) <= vel_tol
        return holds, value


class AtGoal(ObserverKind):
    """Fires while the robot is within ``tol`` of the goal, once the reference has ended.

    The goal is, in order: the ``goal`` input if connected; the ``goal`` parameter (joint
    positions [rad]); else the final point of the Robot-Task's trajectory, in the task
    function's space. A trajectory without an end (``cosine``) ends at the task's
    duration T. With ``vel_tol`` [rad/s] and ``qdot`` connected, the robot must also be
    at rest. ``value`` is the largest distance to the goal.
    """

    name = "at_goal"
    summary = "at the final point of the reference, within tol"
    inputs = (PortSpec("q", "in", "vector", None, True, "joint positions [rad]"),
              PortSpec("goal", "in", "vector", None, False, "goal [rad]"),
              PortSpec("qdot", "in", "vector", None, False, "joint velocities [rad/s]"))
    own_params = (ParamSpec("tol", "float", REQUIRED, "distance tolerance [rad or m]", 0.0, True),
                  ParamSpec("goal", "vector", None, "goal joint positions [rad]"),
                  ParamSpec("vel_tol", "float", None, "speed tolerance [rad/s]", 0.0, True))
    monitor = _AtGoalMonitor

    def check(self, values: Mapping[str, Any], context: ModuleContext) -> None:
        robot = context.robot
        if values["goal"] is not None:
            if robot is not None and len(values["goal"]) != robot.dof:
                raise ControlError(f"{self.name}: goal has {len(values['goal'])} components, "
                                   f"robot {robot.name!r} has {robot.dof} joints")
            return
        if context.task_function is None or robot is None:
            raise ControlError(f"{self.name}: no goal: give goal = [...] or use it in a "
                               "Robot-Task with a task function")
        trajectory = context.task_function.build(robot).trajectory
        if trajectory.end_time_s is None and context.duration_s is None:
            raise ControlError(f"{self.name}: no goal: trajectory {trajectory.name!r} never "
                               "ends and the Robot-Task has no duration; give goal = [...]")
