r"""Dynamic models :math:`\hat M(q)` and :math:`\hat N(q, \dot q)` used by control laws.

RR-1801 eq. 1: :math:`\Gamma = M(q)\ddot q + N(q, \dot q)`. The library offers:

- :class:`IdentityModel` — :math:`\hat M = I`, :math:`\hat N = 0` (PID, §7.1.1);
- :class:`PinocchioModel` — from the robot's MJCF via Pinocchio:
  :math:`\hat M` = CRBA (armature included), :math:`\hat N` = Coriolis, centrifugal and
  gravity (``nonLinearEffects``) plus viscous joint damping;
- :func:`perturbed_model` — a Pinocchio model whose link masses and inertias are scaled
  by random factors in :math:`[1-\delta, 1+\delta]` (seeded), for robustness studies.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from typing import Any

import numpy as np

from orccad_app.control.errors import InvalidParameter

__all__ = ["DynamicsModel", "IdentityModel", "PinocchioModel", "perturbed_model", "MODEL_NAMES"]

#: Names accepted by laws' ``model`` parameter.
MODEL_NAMES: tuple[str, ...] = ("identity", "pinocchio", "perturbed")


class DynamicsModel(ABC):
    """:math:`\\hat M(q)` [kg·m²] and :math:`\\hat N(q, \\dot q)` [N·m] of an n-joint robot."""

    def __init__(self, dof: int):
        self.dof = dof

    @abstractmethod
    def mass_matrix(self, q: np.ndarray) -> np.ndarray:
        """Symmetric positive ``(n, n)`` kinetic energy matrix at ``q`` [rad]."""

    @abstractmethod
    def nonlinear_effects(self, q: np.ndarray, qdot: np.ndarray) -> np.ndarray:
        """Gravity, friction, Coriolis and centrifugal torques at ``(q, qdot)`` [N·m]."""


class IdentityModel(DynamicsModel):
    """:math:`\\hat M = I`, :math:`\\hat N = 0`: no model knowledge."""

    def mass_matrix(self, q: np.ndarray) -> np.ndarray:
        return np.eye(self.dof)

    def nonlinear_effects(self, q: np.ndarray, qdot: np.ndarray) -> np.ndarray:
        return np.zeros(self.dof)


class PinocchioModel(DynamicsModel):
    """Rigid-body model from a ``pinocchio.Model`` (e.g. ``RobotType.pinocchio_model()``).

    ``damping`` [N·m·s/rad] (default ``model.damping``, read from the MJCF) adds viscous
    friction :math:`D \\dot q` to :math:`\\hat N`; MuJoCo applies the same damping as a
    passive force.
    """

    def __init__(self, model: Any, damping: Any = None):
        import pinocchio

        super().__init__(model.nv)
        self._pin = pinocchio
        self.model = model
        self.data = model.createData()
        self.damping = np.array(model.damping if damping is None else damping, dtype=float)

    def mass_matrix(self, q: np.ndarray) -> np.ndarray:
        upper = self._pin.crba(self.model, self.data, np.asarray(q, dtype=float))
        return np.triu(upper) + np.triu(upper, 1).T

    def nonlinear_effects(self, q: np.ndarray, qdot: np.ndarray) -> np.ndarray:
        q = np.asarray(q, dtype=float)
        qdot = np.asarray(qdot, dtype=float)
        bias = self._pin.nonLinearEffects(self.model, self.data, q, qdot)
        return np.array(bias) + self.damping * qdot


def perturbed_model(model: Any, perturbation: float, seed: int = 0) -> PinocchioModel:
    """A :class:`PinocchioModel` with each link's mass and rotational inertia scaled by a
    factor drawn uniformly in ``[1 - perturbation, 1 + perturbation]`` (``seed``-ed);
    centres of mass are unchanged. ``perturbation`` must be in ``[0, 1)``.
    """
    import pinocchio

    if not 0.0 <= perturbation < 1.0:
        raise InvalidParameter(f"perturbed model: perturbation must be in [0, 1), "
                               f"got {perturbation!r}")
    rng = np.random.default_rng(seed)
    changed = model.copy()
    for index in range(1, changed.njoints):
        inertia = changed.inertias[index]
        factor = float(rng.uniform(1.0 - perturbation, 1.0 + perturbation))
        changed.inertias[index] = pinocchio.Inertia(
            inertia.mass * factor, inertia.lever.copy(), inertia.inertia * factor)
    return PinocchioModel(changed)
