"""The task function interface: :class:`TaskFunction` and its :class:`TaskState`."""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass

import numpy as np

from orccad_app.control.errors import DimensionMismatch
from orccad_app.control.trajectories import Sample, Trajectory

__all__ = ["TaskState", "TaskFunction"]


@dataclass(frozen=True, slots=True)
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
    #: unit of the task error ``e`` (reports label its RMS and max with it)
    error_unit: str = "rad"

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
