"""The observers' C: where each kind's C is and the parameter words an instance gives it.

``orccad sil`` and ``orccad codegen --module-tasks`` run ``joint_limits``,
``torque_saturation``, ``tracking_error`` and ``at_rest`` from this plugin's own C file
(``c/observers.c``), carried through :class:`~orccad_app.plugin_api.CImplementation` as a
third-party plugin's kinds are. Every observer's words start with its edge flag; then, in the
order of the file's layout comments:

- ``joint_limits``: the margin [rad], the robot's joint count and its lower and upper limits
  [rad] (from the robot file: the C never reads it);
- ``torque_saturation``: the ratio, the joint count and the actuator constraint's
  ``tau_min``, ``tau_max``, ``alpha``, ``beta``;
- ``tracking_error``: the bound and the error's size; ``at_rest``: the tolerance and the
  speeds' size.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from orccad_app.plugin_api import CImplementation

__all__ = ["AT_REST_C", "JOINT_LIMITS_C", "TORQUE_SATURATION_C", "TRACKING_ERROR_C"]

_SOURCE = Path(__file__).resolve().parent / "c" / "observers.c"


def _floats(values: Any) -> list[float]:
    return [float(v) for v in np.asarray(values, dtype=float).reshape(-1)]


def _observer(words: Callable[[Any], list[float]]) -> Callable[[Any], list[float]]:
    """``words`` after the edge flag every observer's C reads first."""
    def with_edge(instance: Any) -> list[float]:
        return [1.0 if instance.params.get("edge") else 0.0, *words(instance)]
    return with_edge


def _robot(instance: Any) -> Any:
    return instance.monitor.context.robot


def _joint_limits(instance: Any) -> list[float]:
    robot = _robot(instance)
    lower, upper = robot.joint_limits
    return [instance.params["margin"], robot.dof, *_floats(lower), *_floats(upper)]


def _torque_saturation(instance: Any) -> list[float]:
    constraint = _robot(instance).actuator_constraint
    return [instance.params["ratio"], constraint.dim, *_floats(constraint.tau_min),
            *_floats(constraint.tau_max), *_floats(constraint.alpha),
            *_floats(constraint.beta)]


def _input_dims(instance: Any) -> list[int]:
    return [p.dim or 1 for p in instance.ports if p.direction == "in"]


def _tracking_error(instance: Any) -> list[float]:
    return [instance.params["max"], max(_input_dims(instance))]


def _at_rest(instance: Any) -> list[float]:
    return [instance.params["tol"], _input_dims(instance)[0]]


JOINT_LIMITS_C = CImplementation(_SOURCE, "orccad_obs_joint_limits", _observer(_joint_limits))
TORQUE_SATURATION_C = CImplementation(_SOURCE, "orccad_obs_torque_saturation",
                                      _observer(_torque_saturation))
TRACKING_ERROR_C = CImplementation(_SOURCE, "orccad_obs_tracking_error",
                                   _observer(_tracking_error))
AT_REST_C = CImplementation(_SOURCE, "orccad_obs_at_rest", _observer(_at_rest))
