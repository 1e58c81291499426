"""The AUV's kinds in C: where each kind's C is and the parameter words an instance gives it.

``orccad sil`` and ``orccad codegen --module-tasks`` run these kinds from the plugin's own C
files (``c/``), carried through :class:`~orccad_app.plugin_api.CImplementation` as a
third-party plugin's are; the words below are in the order each file's layout comment gives:

- ``c/auv_autopilot.c`` (``auv_autopilot``): the gains, the thrusters' lever arm [m] and limits
  [N] (from :mod:`orccad_auv.vehicle`, the same constants the Python kind uses);
- ``c/auv_guidance.c`` (the six guidance kinds): a mode (0 depth, 1 station, 2 line of sight),
  the depth, speed, station and line-of-sight settings, then the waypoints;
- ``c/auv_observer.c`` (the AUV's observers): the edge flag, the limit and a mode (0 below,
  1 above, 2 a GPS fix held long enough).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from orccad_app.plugin_api import CImplementation, ControlError
from orccad_auv.vehicle import THRUST_LIMITS_N, THRUSTER_ARM_M

__all__ = ["AUTOPILOT_C", "GUIDANCE_C", "observer_c"]

_C = Path(__file__).resolve().parent / "c"
_AUTOPILOT_GAINS = ("kp_depth", "kd_depth", "ki_depth", "max_integral", "max_heave",
                    "kp_pitch", "kd_pitch", "kp_heading", "kd_heading", "k_speed", "drag_coeff")
_GUIDE_HEADER = 10
"""Words of the guidance's layout before its waypoints (``GUIDE_POINTS`` of its C)."""
_MAX_WORDS = 192
"""Parameter words of a Module-Task in the C runtime."""


def _autopilot_words(instance: Any) -> list[float]:
    return [*(float(instance.params[name]) for name in _AUTOPILOT_GAINS), THRUSTER_ARM_M,
            *(float(limit) for limit in THRUST_LIMITS_N)]


def _guidance_words(instance: Any) -> list[float]:
    prm = instance.params
    name = instance.kind.name
    station = name in ("station_guidance", "hold_guidance")
    mode = 0 if name == "depth_guidance" else 1 if station else 2
    points: list[tuple[float, float]] = [] if mode != 2 else instance.kind.waypoints(prm)
    if _GUIDE_HEADER + 2 * len(points) > _MAX_WORDS:
        raise ControlError(f"{len(points)} waypoints, the C runtime holds "
                           f"{(_MAX_WORDS - _GUIDE_HEADER) // 2}")
    header = [float(mode), prm["depth"], prm.get("speed", 0.0), prm.get("x", 0.0),
              prm.get("y", 0.0), prm.get("gain", 0.0), prm.get("max_speed", 0.0),
              prm.get("radius", 0.0), prm.get("lookahead", 1.0), float(len(points))]
    return header + [float(c) for point in points for c in point]


AUTOPILOT_C = CImplementation(_C / "auv_autopilot.c", "orccad_auv_autopilot", _autopilot_words)
"""The autopilot's C."""
GUIDANCE_C = CImplementation(_C / "auv_guidance.c", "orccad_auv_guidance", _guidance_words)
"""The guidance kinds' C (one file, the kind's mode its first word)."""


def observer_c(limit: str, mode: int) -> CImplementation:
    """The C of an AUV observer whose limit is parameter ``limit``: ``mode`` 0 fires below it,
    1 above it, 2 once a GPS fix has held for ``limit`` [s]."""
    def words(instance: Any) -> list[float]:
        return [1.0 if instance.params.get("edge") else 0.0, float(instance.params[limit]),
                float(mode)]
    return CImplementation(_C / "auv_observer.c", "orccad_auv_observer", words)
