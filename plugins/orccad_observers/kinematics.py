"""``singularity(threshold)``: the end effector loses mobility."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from orccad_app.plugin_api import REQUIRED, ControlError, ModuleContext, ParamSpec, PortSpec

from orccad_observers.base import Monitor, ObserverKind

__all__ = ["Singularity", "manipulability"]


def manipulability(jacobian: np.ndarray) -> float:
    """Yoshikawa's :math:`\\sqrt{\\det(J J^T)}` of a (m, n) Jacobian, m <= n."""
    return float(np.sqrt(max(np.linalg.det(jacobian @ jacobian.T), 0.0)))


class _SingularityMonitor(Monitor):
    def __init__(self, params: Mapping[str, Any], context: ModuleContext):
        import pinocchio

        super().__init__(params, context)
        self._pin = pinocchio
        self.model = context.robot.pinocchio_model()
        self.data = self.model.createData()
        self.frame_id = self.model.getFrameId(params["frame"] or context.robot.end_effector)

    def __call__(self, t_s: float, inputs: Mapping[str, Any]) -> tuple[bool, float] | None:
        q = inputs.get("q")
        if q is None:
            return None
        jacobian = self._pin.computeFrameJacobian(
            self.model, self.data, np.asarray(q, dtype=float), self.frame_id,
            self._pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)[:3]
        value = manipulability(jacobian)
        return value < self.params["threshold"], value


class Singularity(ObserverKind):
    """Fires when the manipulability :math:`\\sqrt{\\det(J J^T)}` of the end effector's
    translational Jacobian drops below ``threshold`` [m³/rad³ for 3 joints]."""

    name = "singularity"
    summary = "end-effector manipulability below threshold"
    inputs = (PortSpec("q", "in", "vector", None, True, "joint positions [rad]"),)
    own_params = (
        ParamSpec("threshold", "float", REQUIRED, "manipulability threshold", 0.0, True),
        ParamSpec("frame", "string", None, "frame; default: the robot's end effector"),
    )
    monitor = _SingularityMonitor

    def check(self, values: Mapping[str, Any], context: ModuleContext) -> None:
        robot = context.require_robot(self.name)
        frame = values["frame"] or robot.end_effector
        if frame is None:
            raise ControlError(f"{self.name}: robot type {robot.name!r} has no end "
                               "effector; give frame = \"...\"")
        if not robot.pinocchio_model().existFrame(frame):
            raise ControlError(f"{self.name}: robot type {robot.name!r} has no frame {frame!r}")
