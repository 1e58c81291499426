r"""Task functions :math:`e(q, t)` to regulate to zero (RR-1801 §3.1.2).

A task function evaluates, at :math:`(q, \dot q)` and the reference sample
:math:`(x_d, \dot x_d, \ddot x_d)` of its trajectory, everything eq. 5 needs
(:class:`TaskState`): :math:`e`, :math:`\dot e = J \dot q + \partial e/\partial t`, the
task Jacobian :math:`J = \partial e/\partial q` and a model of its inverse, and
:math:`f` such that :math:`\ddot e = J \ddot q + f` (eq. 3).

- :class:`JointTracking` — :math:`e = q - q_d(t)`, :math:`J = I`, :math:`f = -\ddot q_d`
  (eq. 6–7).
- :class:`CartesianTracking` — :math:`e = p(q) - p_d(t)` for the position of a frame
  (the end effector), :math:`J` its translational Jacobian (Pinocchio, world-aligned),
  :math:`f = \dot J \dot q - \ddot p_d`, and the damped-least-squares inverse
  :math:`J^+ = J^T (J J^T + \lambda^2 I)^{-1}` that stays bounded near singularities.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from orccad_app.control.errors import ControlError, DimensionMismatch
from orccad_app.control.params import REQUIRED, ParamSpec
from orccad_app.control.trajectories import Sample, Trajectory

if TYPE_CHECKING:
    from orccad_app.control.robot import RobotType

__all__ = [
    "TaskState",
    "TaskFunction",
    "JointTracking",
    "CartesianTracking",
    "JOINT_TRACKING",
    "CARTESIAN_TRACKING",
]


@dataclass(frozen=True)
class TaskState:
    """Eq. 2–3 terms at one instant; ``jacobian`` is (m, n), ``jacobian_inv`` (n, m)."""

    e: np.ndarray
    e_dot: np.ndarray
    jacobian: np.ndarray
    jacobian_inv: np.ndarray
    de_dt: np.ndarray
    f: np.ndarray


class TaskFunction(ABC):
    """An m-dimensional task function of an n-joint robot, tracking :attr:`trajectory`."""

    #: kind name, e.g. ``"joint_tracking"``
    name: str = "task_function"
    #: name of the reference the trajectory module sends (``qd`` → ports qd, qd_dot, qd_ddot)
    reference_name: str = "qd"

    def __init__(self, trajectory: Trajectory, dim: int, dof: int):
        self.trajectory = trajectory
        self.dim = dim
        self.dof = dof
        if not trajectory.needs_start and trajectory.dim != dim:
            raise DimensionMismatch(
                f"{self.name}: trajectory {trajectory.name!r} has {trajectory.dim} "
                f"components but the task function has dim e = {dim}")

    @abstractmethod
    def measure(self, q: np.ndarray) -> np.ndarray:
        """The measured quantity the reference is compared with (``q``, ``p(q)``)."""

    @abstractmethod
    def evaluate(self, q: np.ndarray, qdot: np.ndarray, reference: Sample) -> TaskState:
        """Eq. 2–3 terms at ``q`` [rad], ``qdot`` [rad/s] for the ``reference`` sample."""

    def reference(self, t_s: float) -> Sample:
        """The trajectory sampled at ``t_s`` [s] from the start of the task."""
        return self.trajectory.sample(t_s)

    def start_from(self, q: np.ndarray) -> None:
        """Complete a trajectory without start position from the measurement at ``q``."""
        if self.trajectory.needs_start:
            self.trajectory = self.trajectory.with_start(self.measure(q))


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


class CartesianTracking(TaskFunction):
    """:math:`e = p(q) - p_d(t)` for the position of ``frame`` [m]; DLS damping ``λ`` [m]."""

    name = "cartesian_tracking"
    reference_name = "xd"

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
