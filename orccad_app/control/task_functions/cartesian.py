"""Cartesian tracking of a frame's position, with a damped-least-squares inverse."""

from __future__ import annotations

from typing import Any

import numpy as np

from orccad_app.control.errors import ControlError
from orccad_app.control.task_functions.base import TaskFunction, TaskState
from orccad_app.control.trajectories import Sample, Trajectory

__all__ = ["CartesianTracking"]


class CartesianTracking(TaskFunction):
    """:math:`e = p(q) - p_d(t)` for the position of ``frame`` [m]; DLS damping ``λ`` [m]."""

    name = "cartesian_tracking"
    reference_name = "xd"
    error_unit = "m"

    def __init__(self, pin_model: Any, trajectory: Trajectory, frame: str,
                 damping: float = 0.01):
        import pinocchio

        if not pin_model.existFrame(frame):
            names = [f.name for f in pin_model.frames]
            raise ControlError(f"{self.name}: the robot has no frame {frame!r}; "
                               f"frames: {', '.join(names)}")
        super().__init__(trajectory, 3, pin_model.nv)
        self._pin = pinocchio
        self.model = pin_model
        self.data = pin_model.createData()
        self.frame = frame
        self.frame_id = pin_model.getFrameId(frame)
        self.damping = float(damping)
        self._world = pinocchio.ReferenceFrame.LOCAL_WORLD_ALIGNED

    def _kinematics(self, q: np.ndarray, qdot: np.ndarray) -> tuple[np.ndarray, ...]:
        pin, model, data = self._pin, self.model, self.data
        pin.computeJointJacobians(model, data, q)
        pin.forwardKinematics(model, data, q, qdot, np.zeros(model.nv))
        pin.updateFramePlacements(model, data)
        jacobian = pin.getFrameJacobian(model, data, self.frame_id, self._world)[:3]
        bias = pin.getFrameClassicalAcceleration(model, data, self.frame_id, self._world)
        return data.oMf[self.frame_id].translation.copy(), jacobian, np.array(bias.linear)

    def measure(self, q: np.ndarray) -> np.ndarray:
        q = np.asarray(q, dtype=float)
        self._pin.framesForwardKinematics(self.model, self.data, q)
        return self.data.oMf[self.frame_id].translation.copy()

    def jacobian(self, q: np.ndarray) -> np.ndarray:
        """Translational Jacobian (3, n) of the frame at ``q``, world-aligned [m/rad]."""
        q = np.asarray(q, dtype=float)
        return self._kinematics(q, np.zeros(self.model.nv))[1]

    def dls_inverse(self, jacobian: np.ndarray) -> np.ndarray:
        """:math:`J^T (J J^T + \\lambda^2 I)^{-1}` (the pseudo-inverse when λ = 0)."""
        if self.damping == 0.0:
            return np.linalg.pinv(jacobian)
        gram = jacobian @ jacobian.T + self.damping ** 2 * np.eye(jacobian.shape[0])
        return jacobian.T @ np.linalg.inv(gram)

    def evaluate(self, q: np.ndarray, qdot: np.ndarray, reference: Sample) -> TaskState:
        q = np.asarray(q, dtype=float)
        qdot = np.asarray(qdot, dtype=float)
        position, jacobian, jdot_qdot = self._kinematics(q, qdot)
        return TaskState(e=position - reference.pos,
                         e_dot=jacobian @ qdot - reference.vel,
                         jacobian=jacobian, jacobian_inv=self.dls_inverse(jacobian),
                         de_dt=-reference.vel, f=jdot_qdot - reference.acc)
