"""Joint-space tracking, RR-1801 eq. 6–7."""

from __future__ import annotations

import numpy as np

from orccad_app.control.task_functions.base import TaskFunction, TaskState
from orccad_app.control.trajectories import Sample, Trajectory

__all__ = ["JointTracking"]


class JointTracking(TaskFunction):
    """:math:`e = q - q_d(t)` (eq. 6); units [rad]."""

    name = "joint_tracking"
    reference_name = "qd"

    def __init__(self, dof: int, trajectory: Trajectory):
        super().__init__(trajectory, dof, dof)
        self._eye = np.eye(dof)

    def measure(self, q: np.ndarray) -> np.ndarray:
        return np.asarray(q, dtype=float)

    def evaluate(self, q: np.ndarray, qdot: np.ndarray, reference: Sample) -> TaskState:
        q = np.asarray(q, dtype=float)
        qdot = np.asarray(qdot, dtype=float)
        return TaskState(e=q - reference.pos, e_dot=qdot - reference.vel,
                         jacobian=self._eye, jacobian_inv=self._eye,
                         de_dt=-reference.vel, f=-reference.acc)
