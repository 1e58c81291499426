r"""Actuator constraints of RR-1801 §3.1.2.

.. math::

    \max(\Gamma^{min}_i, -\alpha_i - \beta_i \dot q_i) \le \Gamma_i
        \le \min(\Gamma^{max}_i, \alpha_i - \beta_i \dot q_i)

:math:`\Gamma^{min}, \Gamma^{max}` [N·m] are the drive's current (torque) limits;
:math:`\alpha` [N·m] and :math:`\beta` [N·m·s/rad] describe the motor's torque–speed line
(stall torque and back-EMF slope). With :math:`\alpha = \infty` the constraint is plain
torque saturation.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from orccad_app.control.errors import DimensionMismatch, InvalidParameter

__all__ = ["ActuatorConstraint"]


def _vector(name: str, value: Any, dim: int | None) -> np.ndarray:
    array = np.array(value, dtype=float).reshape(-1)
    if dim is not None and array.size == 1:
        array = np.full(dim, array[0])
    if dim is not None and array.size != dim:
        raise DimensionMismatch(f"actuator constraint: {name} has {array.size} values, "
                                f"expected {dim}")
    array.setflags(write=False)
    return array


class ActuatorConstraint:
    """Torque bounds depending on joint velocity; see the module docstring.

    ``tau_min`` < ``tau_max`` [N·m] per joint; ``alpha`` > 0 [N·m] (default ``inf``);
    ``beta`` >= 0 [N·m·s/rad] (default 0). Scalars are broadcast to every joint.
    """

    def __init__(self, tau_min: Any, tau_max: Any, alpha: Any = np.inf, beta: Any = 0.0):
        self.tau_max = _vector("tau_max", tau_max, None)
        dim = self.tau_max.size
        self.tau_min = _vector("tau_min", tau_min, dim)
        self.alpha = _vector("alpha", alpha, dim)
        self.beta = _vector("beta", beta, dim)
        if np.any(self.tau_min >= self.tau_max):
            raise InvalidParameter(f"actuator constraint: tau_min {self.tau_min.tolist()} "
                                   f"must be < tau_max {self.tau_max.tolist()}")
        if np.any(self.alpha <= 0):
            raise InvalidParameter(f"actuator constraint: alpha must be > 0, "
                                   f"got {self.alpha.tolist()}")
        if np.any(self.beta < 0) or not np.all(np.isfinite(self.beta)):
            raise InvalidParameter(f"actuator constraint: beta must be finite and >= 0, "
                                   f"got {self.beta.tolist()}")

    @property
    def dim(self) -> int:
        """Number of actuated joints."""
        return self.tau_max.size

    def bounds(self, qdot: Any) -> tuple[np.ndarray, np.ndarray]:
        """``(low, high)`` [N·m] at joint velocity ``qdot`` [rad/s].

        Where the torque–speed range and the current limits do not meet (very high
        speed), the current limit wins: ``low == high``.
        """
        qdot = np.asarray(qdot, dtype=float)
        if qdot.shape != (self.dim,):
            raise DimensionMismatch(f"actuator constraint: qdot has shape {qdot.shape}, "
                                    f"expected ({self.dim},)")
        with np.errstate(invalid="ignore"):
            back_emf = np.where(self.beta == 0.0, 0.0, self.beta * qdot)
        low = np.maximum(self.tau_min, -self.alpha - back_emf)
        high = np.minimum(self.tau_max, self.alpha - back_emf)
        high = np.maximum(high, np.minimum(low, self.tau_max))
        low = np.minimum(low, high)
        return low, high

    def apply(self, tau: Any, qdot: Any) -> tuple[np.ndarray, np.ndarray]:
        """``(clipped torque [N·m], saturated mask)``: which joints hit a bound."""
        tau = np.asarray(tau, dtype=float)
        if tau.shape != (self.dim,):
            raise DimensionMismatch(f"actuator constraint: tau has shape {tau.shape}, "
                                    f"expected ({self.dim},)")
        low, high = self.bounds(qdot)
        clipped = np.clip(tau, low, high)
        return clipped, clipped != tau

    def at_bound(self, tau: Any, qdot: Any, tol: float = 1e-9) -> np.ndarray:
        """Mask of joints whose torque is at or beyond a bound (within ``tol`` [N·m])."""
        low, high = self.bounds(qdot)
        tau = np.asarray(tau, dtype=float)
        return (tau >= high - tol) | (tau <= low + tol)

    def __repr__(self) -> str:
        return (f"ActuatorConstraint(tau_min={self.tau_min.tolist()}, "
                f"tau_max={self.tau_max.tolist()}, alpha={self.alpha.tolist()}, "
                f"beta={self.beta.tolist()})")
