"""The AUV's observers (default 100 ms period, 0.1 ms WCET).

========================  ============  ===============================================
``battery_low(min)``      ``battery``   the charge is below ``min`` [%] (type 2 in the
                                        missions: end the survey and surface)
``leak``                  ``leak``      the leak detector is wet (type 3)
``depth_limit(max)``      ``depth``     deeper than ``max`` [m] (type 3)
``altitude_low(min)``     ``altitude``  closer than ``min`` [m] to the seabed (type 2)
``at_waypoint(tol)``      ``goal_error``  the guidance's goal is within ``tol`` [m]
                                        (post-condition)
``gps_fix(acquire)``      ``gps``       a GPS fix held for ``acquire`` [s] (measurement
                                        pre-condition at the surface, with a watchdog)
========================  ============  ===============================================

Each input is wired by name: the robot's sensor port or the guidance module's output.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from orccad_app.plugin_api import ParamSpec, PortSpec, Timing
from orccad_auv.c_kinds import observer_c
from orccad_observers import Monitor, ObserverKind

__all__ = ["BatteryLow", "Leak", "DepthLimit", "AltitudeLow", "AtWaypoint", "GpsFix",
           "OBSERVERS"]

_TIMING = Timing.from_ms(100.0, 0.1)


def _value(inputs: Mapping[str, Any], port: str) -> float | None:
    value = inputs.get(port)
    return None if value is None else float(np.asarray(value, dtype=float).reshape(-1)[0])


class _Threshold(Monitor):
    """``port`` compared with a parameter: below ``min`` or above ``max``."""

    port = ""
    bound = "min"

    def __call__(self, t_s: float, inputs: Mapping[str, Any]) -> tuple[bool, float] | None:
        value = _value(inputs, self.port)
        if value is None:
            return None
        limit = self.params[self.bound]
        return (value < limit if self.bound in ("min", "tol") else value > limit), value


def _float_input(port: str, doc: str) -> tuple[PortSpec, ...]:
    return (PortSpec(port, "in", "float", None, True, doc),)


class _BatteryMonitor(_Threshold):
    port = "battery"


class BatteryLow(ObserverKind):
    """The battery charge is below ``min`` [%]."""

    name = "battery_low"
    summary = "AUV battery charge below min [%]"
    inputs = _float_input("battery", "battery charge [%]")
    own_params = (ParamSpec("min", "float", 20.0, "charge bound [%]", 0.0),)
    monitor = _BatteryMonitor
    default_timing = _TIMING
    c_implementation = observer_c("min", 0)


class _LeakMonitor(_Threshold):
    port = "leak"
    bound = "max"


class Leak(ObserverKind):
    """The leak detector is wet."""

    name = "leak"
    summary = "AUV leak detector wet"
    inputs = _float_input("leak", "leak detector [0/1]")
    own_params = (ParamSpec("max", "float", 0.5, "detector threshold [-]", 0.0),)
    monitor = _LeakMonitor
    default_timing = _TIMING
    c_implementation = observer_c("max", 1)


class _DepthMonitor(_Threshold):
    port = "depth"
    bound = "max"


class DepthLimit(ObserverKind):
    """Deeper than ``max`` [m]."""

    name = "depth_limit"
    summary = "AUV deeper than max [m]"
    inputs = _float_input("depth", "depth [m]")
    own_params = (ParamSpec("max", "float", 30.0, "maximum depth [m]", 0.0, True),)
    monitor = _DepthMonitor
    default_timing = _TIMING
    c_implementation = observer_c("max", 1)


class _AltitudeMonitor(_Threshold):
    port = "altitude"


class AltitudeLow(ObserverKind):
    """Closer than ``min`` [m] to the seabed."""

    name = "altitude_low"
    summary = "AUV closer than min [m] to the seabed"
    inputs = _float_input("altitude", "altitude above the seabed [m]")
    own_params = (ParamSpec("min", "float", 5.0, "minimum altitude [m]", 0.0, True),)
    monitor = _AltitudeMonitor
    default_timing = _TIMING
    c_implementation = observer_c("min", 0)


class _GoalMonitor(_Threshold):
    port = "goal_error"
    bound = "tol"


class AtWaypoint(ObserverKind):
    """The guidance's goal error is below ``tol`` [m]."""

    name = "at_waypoint"
    summary = "AUV guidance goal reached within tol [m]"
    inputs = (PortSpec("goal_error", "in", "vector", 1, True,
                       "distance to the guidance's goal [m]"),)
    own_params = (ParamSpec("tol", "float", 2.0, "tolerance [m]", 0.0, True),)
    monitor = _GoalMonitor
    default_timing = _TIMING
    c_implementation = observer_c("tol", 0)

    def input_dims(self, values: Mapping[str, Any], context: Any) -> dict[str, int]:
        return {"goal_error": 1}


class _GpsMonitor(Monitor):
    def reset(self) -> None:
        self.since = None

    def __call__(self, t_s: float, inputs: Mapping[str, Any]) -> tuple[bool, float] | None:
        value = _value(inputs, "gps")
        if value is None:
            return None
        if value < 0.5:
            self.since = None
            return False, 0.0
        if self.since is None:
            self.since = t_s
        held = t_s - self.since
        return held >= self.params["acquire"], held


class GpsFix(ObserverKind):
    """A GPS fix held for ``acquire`` [s]; ``value`` is how long it has held [s]."""

    name = "gps_fix"
    summary = "AUV GPS fix held for acquire [s] (at the surface)"
    inputs = _float_input("gps", "GPS fix [0/1]")
    own_params = (ParamSpec("acquire", "float", 2.0, "time to a fix [s]", 0.0),)
    monitor = _GpsMonitor
    default_timing = _TIMING
    c_implementation = observer_c("acquire", 2)


OBSERVERS = (BatteryLow(), Leak(), DepthLimit(), AltitudeLow(), AtWaypoint(), GpsFix())
