"""``sensor_threshold(sensor, direction, value)``: a robot sensor crosses a threshold."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from orccad_app.plugin_api import REQUIRED, ControlError, ModuleContext, ParamSpec, PortSpec

from orccad_observers.base import Monitor, ObserverKind

__all__ = ["SensorThreshold"]


class _SensorThresholdMonitor(Monitor):
    def __call__(self, t_s: float, inputs: Mapping[str, Any]) -> tuple[bool, float] | None:
        signal = inputs.get("signal")
        if signal is None:
            return None
        data = np.atleast_1d(np.asarray(signal, dtype=float))
        if self.params["index"] is not None:
            data = data[self.params["index"]: self.params["index"] + 1]
        if self.params["absolute"]:
            data = np.abs(data)
        if self.params["direction"] == "above":
            value = float(np.max(data))
            return value > self.params["value"], value
        value = float(np.min(data))
        return value < self.params["value"], value


class SensorThreshold(ObserverKind):
    """Fires while a component of the robot sensor ``sensor`` (e.g. ``"qdot"``) is
    ``above`` (or ``below``) ``value``; ``index`` watches one component only, ``absolute``
    compares magnitudes. The input port ``signal`` reads ``ROBOT.<sensor>`` (see
    :meth:`sources`); ``value`` out is the extreme component."""

    name = "sensor_threshold"
    summary = "a robot sensor goes above / below a value"
    inputs = (PortSpec("signal", "in", "vector", None, True, "the sensor's reading"),)
    own_params = (
        ParamSpec("sensor", "string", REQUIRED, "robot sensor port, e.g. \"qdot\""),
        ParamSpec("direction", "string", REQUIRED, "above or below", choices=("above", "below")),
        ParamSpec("value", "float", REQUIRED, "threshold, in the sensor's unit"),
        ParamSpec("index", "int", None, "watch this component only (0-based)", 0.0),
        ParamSpec("absolute", "bool", False, "compare absolute values"),
    )
    monitor = _SensorThresholdMonitor

    def sources(self, params: Mapping[str, Any]) -> dict[str, str]:
        """``signal`` reads the robot port named by the ``sensor`` parameter."""
        return {"signal": str(params.get("sensor", "signal"))}

    def input_dims(self, values: Mapping[str, Any], context: ModuleContext) -> dict[str, int]:
        if context.robot is None:
            return {}
        return {"signal": context.robot.port(values["sensor"]).dim}

    def check(self, values: Mapping[str, Any], context: ModuleContext) -> None:
        robot = context.robot
        if robot is None:
            return
        port = robot.port(values["sensor"])
        if port.spec.direction != "out":
            names = ", ".join(p.name for p in robot.sensors)
            raise ControlError(f"{self.name}: {values['sensor']!r} is an actuator of robot "
                               f"type {robot.name!r}, not a sensor; sensors: {names}")
        index = values["index"]
        if index is not None and index >= port.dim:
            raise ControlError(f"{self.name}: index {index} is out of range for sensor "
                               f"{values['sensor']!r} of {port.dim} components")
