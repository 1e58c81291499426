"""Observers of physical limits: ``joint_limits(margin)`` and ``torque_saturation``."""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from orccad_app.plugin_api import ControlError, ModuleContext, ParamSpec, PortSpec

from orccad_observers.base import Monitor, ObserverKind
from orccad_observers.c_kinds import JOINT_LIMITS_C, TORQUE_SATURATION_C

__all__ = ["JointLimits", "TorqueSaturation"]


SCALAR_DIM = 8
"""Vectors of at most this many components are checked on Python floats (numpy's per-call
overhead is most of the cost for a few joints). The operations are the numpy ones in the same
order, with numpy's tie rules — ``np.minimum``/``np.maximum`` return their second operand on a
tie, and ``np.min``/``np.max`` reduce left to right keeping the later element on a tie (checked
up to 8 components) — so the monitored values are bit-identical; non-finite inputs take the
numpy path."""


def _least(values: list[float]) -> float:
    """``np.min(values)`` for at most :data:`SCALAR_DIM` finite values."""
    least = values[0]
    for value in values[1:]:
        if not least < value:
            least = value
    return least


def _greatest(values: list[float]) -> float:
    """``np.max(values)`` for at most :data:`SCALAR_DIM` values without NaN."""
    greatest = values[0]
    for value in values[1:]:
        if not greatest > value:
            greatest = value
    return greatest


def _finite_list(array: np.ndarray, dim: int) -> list[float] | None:
    """``array`` as a list of floats when it has ``dim`` <= 8 finite components."""
    if array.shape != (dim,) or dim > SCALAR_DIM or dim == 0:
        return None
    values = array.tolist()
    return values if math.isfinite(sum(values)) else None


class _JointLimitsMonitor(Monitor):
    def __call__(self, t_s: float, inputs: Mapping[str, Any]) -> tuple[bool, float] | None:
        q = inputs.get("q")
        if q is None:
            return None
        lower, upper = self.context.robot.joint_limits
        q = np.asarray(q, dtype=float)
        values = _finite_list(q, lower.size)
        if values is None:
            distance = float(np.min(np.minimum(q - lower, upper - q)))
        else:
            nearest = []
            for x, low, high in zip(values, lower.tolist(), upper.tolist()):
                below, above = x - low, high - x
                nearest.append(below if below < above else above)  # np.minimum
            distance = _least(nearest)
        return distance < self.params["margin"], distance


class JointLimits(ObserverKind):
    """Fires when a joint is within ``margin`` [rad] of a limit; ``value`` is the smallest
    distance to a limit [rad] (negative beyond it). RR-1801 §7.1's type-3 observer."""

    name = "joint_limits"
    summary = "a joint is within margin [rad] of one of its limits"
    inputs = (PortSpec("q", "in", "vector", None, True, "joint positions [rad]"),)
    own_params = (ParamSpec("margin", "float", 0.1, "distance to the limit [rad]", 0.0),)
    monitor = _JointLimitsMonitor
    c_implementation = JOINT_LIMITS_C

    def check(self, values: Mapping[str, Any], context: ModuleContext) -> None:
        robot = context.require_robot(self.name)
        lower, upper = robot.joint_limits
        half = 0.5 * (upper - lower)
        for joint, room in zip(robot.resources, half):
            if values["margin"] >= room:
                raise ControlError(
                    f"{self.name}: margin {values['margin']!r} rad leaves no room in the "
                    f"range of joint {joint!r} (half-range {room:g} rad)")


class _TorqueSaturationMonitor(Monitor):
    def __call__(self, t_s: float, inputs: Mapping[str, Any]) -> tuple[bool, float] | None:
        tau = inputs.get("tau")
        if tau is None:
            return None
        constraint = self.context.robot.actuator_constraint
        tau = np.asarray(tau, dtype=float)
        qdot = inputs.get("qdot")
        qdot = np.zeros_like(tau) if qdot is None else np.asarray(qdot, dtype=float)
        torques = _finite_list(tau, constraint.dim)
        speeds = _finite_list(qdot, constraint.dim) if torques is not None else None
        if speeds is not None and torques is not None:
            peak = self._peak(constraint, torques, speeds)
        else:
            low, high = constraint.bounds(qdot)
            with np.errstate(divide="ignore", invalid="ignore"):
                usage = np.where(tau > 0, np.where(high > 0, tau / high, np.inf),
                                 np.where(tau < 0, np.where(low < 0, tau / low, np.inf), 0.0))
            peak = float(np.max(usage))
        return peak >= self.params["ratio"] - 1e-9, peak

    @staticmethod
    def _peak(constraint: Any, torques: list[float], speeds: list[float]) -> float:
        """The largest used fraction, on floats: ``constraint.bounds`` and the ``usage``
        expression of the numpy path, operation for operation."""
        usage = []
        for tau, qdot, tau_min, tau_max, alpha, beta in zip(
                torques, speeds, constraint.tau_min.tolist(), constraint.tau_max.tolist(),
                constraint.alpha.tolist(), constraint.beta.tolist()):
            back_emf = 0.0 if beta == 0.0 else beta * qdot
            low = -alpha - back_emf
            if tau_min > low:
                low = tau_min                        # np.maximum(tau_min, low)
            high = alpha - back_emf
            if tau_max < high:
                high = tau_max                       # np.minimum(tau_max, high)
            floor = low if low < tau_max else tau_max
            if not high > floor:
                high = floor                         # np.maximum(high, floor)
            if not low < high:
                low = high                           # np.minimum(low, high)
            if tau > 0:
                usage.append(tau / high if high > 0 else math.inf)
            elif tau < 0:
                usage.append(tau / low if low < 0 else math.inf)
            else:
                usage.append(0.0)
        return _greatest(usage)


class TorqueSaturation(ObserverKind):
    """Fires when a torque uses ``ratio`` (default all) of its bound under the actuator
    constraint at the current ``qdot`` (zero velocity if unconnected); ``value`` is the
    largest used fraction [-]."""

    name = "torque_saturation"
    summary = "a commanded torque reaches its (velocity-dependent) bound"
    inputs = (PortSpec("tau", "in", "vector", None, True, "commanded torques [N·m]"),
              PortSpec("qdot", "in", "vector", None, False, "joint velocities [rad/s]"))
    own_params = (ParamSpec("ratio", "float", 1.0, "fraction of the bound that fires [-]",
                            0.0, True),)
    monitor = _TorqueSaturationMonitor
    c_implementation = TORQUE_SATURATION_C

    def check(self, values: Mapping[str, Any], context: ModuleContext) -> None:
        context.require_robot(self.name)
