"""Observers of physical limits: ``joint_limits(margin)`` and ``torque_saturation``."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from orccad_app.plugin_api import ControlError, ModuleContext, ParamSpec, PortSpec

from orccad_observers.base import Monitor, ObserverKind

__all__ = ["JointLimits", "TorqueSaturation"]


class _JointLimitsMonitor(Monitor):
    def __call__(self, t_s: float, inputs: Mapping[str, Any]) -> tuple[bool, float] | None:
        q = inputs.get("q")
        if q is None:
            return None
        lower, upper = self.context.robot.joint_limits
        q = np.asarray(q, dtype=float)
        distance = float(np.min(np.minimum(q - lower, upper - q)))
        return distance < self.params["margin"], distance


class JointLimits(ObserverKind):
    """Fires when a joint is within ``margin`` [rad] of a limit; ``value`` is the smallest
    distance to a limit [rad] (negative beyond it). RR-1801 §7.1's type-3 observer."""

    name = "joint_limits"
    summary = "a joint is within margin [rad] of one of its limits"
    inputs = (PortSpec("q", "in", "vector", None, True, "joint positions [rad]"),)
    own_params = (ParamSpec("margin", "float", 0.1, "distance to the limit [rad]", 0.0),)
    monitor = _JointLimitsMonitor

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
        low, high = constraint.bounds(qdot)
        with np.errstate(divide="ignore", invalid="ignore"):
            usage = np.where(tau > 0, np.where(high > 0, tau / high, np.inf),
                             np.where(tau < 0, np.where(low < 0, tau / low, np.inf), 0.0))
        peak = float(np.max(usage))
        return peak >= self.params["ratio"] - 1e-9, peak


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

    def check(self, values: Mapping[str, Any], context: ModuleContext) -> None:
        context.require_robot(self.name)
