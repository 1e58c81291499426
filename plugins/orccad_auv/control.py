"""Guidance and control of the AUV: the task functions and the control law, as module kinds.

An AUV Robot-Task is two Module-Tasks: a **guidance** module (the task function: what the
vehicle must achieve, as a setpoint and a goal error) feeding the **autopilot** (the control
law: depth, pitch, heading and speed loops, then thruster allocation).

Guidance kinds (default 100 ms period), in ``position``, ``attitude``; out ``setpoint`` =
[depth [m], heading [rad], surge speed u [m/s], sway speed v [m/s]] and ``goal_error``
(distance to the goal [m], 1e9 while the goal is not the current target; a 1-vector, so that
an observer reads no value, rather than a zero, before the guidance's first job):

``depth_guidance(depth)``
    go to ``depth`` holding the heading of the first job (Dive, Surface).
``los_guidance(x, y, depth)``
    line-of-sight waypoint following to (x, y) at ``depth`` (GoTo).
``lawnmower_guidance(area, spacing, depth)``
    line-of-sight along the lanes of the rectangle ``area`` = [x0, y0, x1, y1] [m], lanes along
    x every ``spacing`` [m]; starts from the lane point nearest to the vehicle (a survey that
    is resumed continues where it stopped).
``station_guidance(x, y, depth)``
    station keeping: holds (x, y, depth) and the heading of the first job with surge and sway.
``waypoint_guidance(target)``, ``hold_guidance(target)``
    ``los_guidance`` and ``station_guidance`` to the waypoint ``target`` = [x, y, depth] [m]
    given as one vector (a waypoint received as a valued input, ``run GoTo(target =
    ?Waypoint)``): exactly 3 finite components, the depth >= 0.

Line of sight: on the leg a → b, cross-track error ``e`` (positive left of the leg), heading
``ψ = atan2(b - a) - atan(e / lookahead)``; the next waypoint when within ``radius``; the speed
slows down within ``4 u / 1 m`` of the last one.

``auv_autopilot`` (default 50 ms period), in ``setpoint``, ``depth``, ``attitude``, ``velocity``;
out ``tau`` (the five thruster forces [N]):

- depth: heave force ``Z = kp_depth (d - d_ref) + kd_depth ḋ + ki_depth ∫(d - d_ref)``
  (world vertical, saturated at ``max_heave``; the integral is clamped to ``max_integral``);
- pitch: ``M = -kp_pitch θ - kd_pitch q`` (level);
- heading: ``N = kp_heading wrap(ψ_ref - ψ) - kd_heading r``;
- speeds: ``X = k_speed (u_ref - u) + drag_coeff u_ref |u_ref|``, ``Y = k_speed (v_ref - v)``;
- allocation: vertical thrusters ``F_fore,aft = (Z ∓ M / l) / 2``, lateral ``(Y ± N / l) / 2``
  with ``l`` = 0.6 m, each clamped to its limit.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from orccad_app.plugin_api import (
    ControlError,
    DimensionMismatch,
    InvalidParameter,
    ModuleInstance,
    ModuleKind,
    ParamSpec,
    PortSpec,
    Timing,
)

from orccad_auv.c_kinds import AUTOPILOT_C, GUIDANCE_C
from orccad_auv.vehicle import THRUST_LIMITS_N, THRUSTER_ARM_M

__all__ = ["DepthGuidance", "LosGuidance", "LawnmowerGuidance", "StationGuidance",
           "WaypointGuidance", "HoldGuidance", "Autopilot", "MODULE_KINDS", "wrap"]

FAR_M = 1e9
"""``goal_error`` while the goal is not the current target [m]."""

POSITION_BOUND_M = 1e6
"""Largest |x|, |y| and depth of a waypoint, a station or an area [m], as the trajectories'
positions: a farther one (``Waypoint([1e308, 0, 5])``) is refused, located, before the
guidance squares it into an overflow."""


def wrap(angle: float) -> float:
    """``angle`` in (-π, π] [rad]."""
    return math.atan2(math.sin(angle), math.cos(angle))


def _scalar(value: Any) -> float:
    return float(np.asarray(value, dtype=float).reshape(-1)[0])


_GUIDE_PORTS = (
    PortSpec("position", "in", "vector", 3, True, "x, y [m], depth [m]"),
    PortSpec("attitude", "in", "vector", 3, True, "roll, pitch, yaw [rad]"),
    PortSpec("setpoint", "out", "vector", 4, True, "depth [m], heading [rad], u, v [m/s]"),
    PortSpec("goal_error", "out", "vector", 1, True,
             "distance to the goal [m] (a vector: no value before the first job)"),
)
_DEPTH = ParamSpec("depth", "float", 10.0, "target depth [m]", 0.0,
                   maximum=POSITION_BOUND_M)
_SPEED = ParamSpec("speed", "float", 1.5, "cruise speed [m/s]", 0.0, True)
_LOS = (ParamSpec("radius", "float", 3.0, "waypoint acceptance radius [m]", 0.0, True),
        ParamSpec("lookahead", "float", 6.0, "line-of-sight lookahead [m]", 0.0, True))


class _Guidance(ModuleKind):
    ports = _GUIDE_PORTS
    default_timing = Timing.from_ms(100.0, 1.0)
    c_implementation = GUIDANCE_C

    def _instantiate(self, values: dict[str, Any], context: Any) -> ModuleInstance:
        return _GuidanceInstance(self, values, self.ports)

    def waypoints(self, params: Mapping[str, Any]) -> list[tuple[float, float]]:
        """The horizontal waypoints [m] (LOS kinds)."""
        return []


class DepthGuidance(_Guidance):
    """Go to a depth, holding the heading."""

    name = "depth_guidance"
    summary = "AUV task function: reach a depth [m] holding the heading"
    params = (_DEPTH, ParamSpec("speed", "float", 0.0, "surge speed [m/s]", 0.0))


class LosGuidance(_Guidance):
    """Line-of-sight guidance to one waypoint."""

    name = "los_guidance"
    summary = "AUV task function: line-of-sight to the waypoint (x, y) [m] at depth [m]"
    params = (ParamSpec("x", "float", 0.0, "waypoint x [m]", -POSITION_BOUND_M,
                        maximum=POSITION_BOUND_M),
              ParamSpec("y", "float", 0.0, "waypoint y [m]", -POSITION_BOUND_M,
                        maximum=POSITION_BOUND_M), _DEPTH, _SPEED) + _LOS

    def waypoints(self, params: Mapping[str, Any]) -> list[tuple[float, float]]:
        return [(params["x"], params["y"])]


class LawnmowerGuidance(_Guidance):
    """Line-of-sight along the lanes of a rectangle."""

    name = "lawnmower_guidance"
    summary = "AUV task function: lawnmower survey of area [x0, y0, x1, y1] [m] at depth"
    params = (ParamSpec("area", "vector", [10.0, 0.0, 50.0, 20.0], "x0, y0, x1, y1 [m]",
                        -POSITION_BOUND_M, maximum=POSITION_BOUND_M),
              ParamSpec("spacing", "float", 10.0, "lane spacing [m]", 0.0, True),
              _DEPTH, _SPEED) + _LOS

    def waypoints(self, params: Mapping[str, Any]) -> list[tuple[float, float]]:
        area = np.asarray(params["area"], dtype=float)
        if area.shape != (4,) or area[2] <= area[0] or area[3] < area[1]:
            raise ControlError(f"lawnmower_guidance: area must be [x0, y0, x1, y1] with "
                               f"x1 > x0 and y1 >= y0, got {area.tolist()}")
        lanes = int(math.floor((area[3] - area[1]) / params["spacing"] + 1e-9)) + 1
        points = []
        for lane in range(lanes):
            y = float(area[1] + lane * params["spacing"])
            ends = [(float(area[0]), y), (float(area[2]), y)]
            points += ends if lane % 2 == 0 else ends[::-1]
        return points


class StationGuidance(_Guidance):
    """Station keeping at (x, y, depth)."""

    name = "station_guidance"
    summary = "AUV task function: station keeping at (x, y) [m] and depth [m]"
    params = (ParamSpec("x", "float", 0.0, "station x [m]", -POSITION_BOUND_M,
                        maximum=POSITION_BOUND_M),
              ParamSpec("y", "float", 0.0, "station y [m]", -POSITION_BOUND_M,
                        maximum=POSITION_BOUND_M),
              ParamSpec("depth", "float", 0.0, "station depth [m]", 0.0,
                        maximum=POSITION_BOUND_M),
              ParamSpec("gain", "float", 0.2, "position gain [1/s]", 0.0, True),
              ParamSpec("max_speed", "float", 0.5, "speed bound [m/s]", 0.0, True))


_TARGET = ParamSpec("target", "vector", [10.0, 0.0, 10.0], "waypoint [x, y, depth] [m]",
                    -POSITION_BOUND_M, maximum=POSITION_BOUND_M)


def _waypoint(kind: str, values: dict[str, Any]) -> dict[str, Any]:
    """``values`` with ``x``, ``y``, ``depth`` taken from the vector ``target``, checked."""
    target = np.asarray(values["target"], dtype=float)
    if target.shape != (3,):
        raise DimensionMismatch(f"{kind}: target must be [x, y, depth] (3 components), got "
                                f"{target.size}: {target.tolist()}")
    if target[2] < 0.0:
        raise InvalidParameter(f"{kind}: the depth of target must be >= 0 m, got "
                               f"{target.tolist()}")
    return {**values, "x": float(target[0]), "y": float(target[1]), "depth": float(target[2])}


class WaypointGuidance(LosGuidance):
    """Line-of-sight guidance to one waypoint given as a vector [x, y, depth]."""

    name = "waypoint_guidance"
    summary = "AUV task function: line-of-sight to the waypoint target = [x, y, depth] [m]"
    params = (_TARGET, _SPEED) + _LOS

    def _instantiate(self, values: dict[str, Any], context: Any) -> ModuleInstance:
        return _GuidanceInstance(self, _waypoint(self.name, values), self.ports)


class HoldGuidance(StationGuidance):
    """Station keeping at a waypoint given as a vector [x, y, depth]."""

    name = "hold_guidance"
    summary = "AUV task function: station keeping at target = [x, y, depth] [m]"
    params = (_TARGET,) + StationGuidance.params[3:]

    def _instantiate(self, values: dict[str, Any], context: Any) -> ModuleInstance:
        return _GuidanceInstance(self, _waypoint(self.name, values), self.ports)


class _GuidanceInstance(ModuleInstance):
    def init(self) -> None:
        super().init()
        self.heading = None
        self.points = self.kind.waypoints(self.params)
        self.index = None

    def compute(self, t_s: float, inputs: Mapping[str, Any]) -> dict[str, Any]:
        position, attitude = inputs.get("position"), inputs.get("attitude")
        if position is None or attitude is None:
            return {}
        p = np.asarray(position, dtype=float)
        yaw = float(np.asarray(attitude)[2])
        if self.heading is None:
            self.heading = yaw
        name = self.kind.name
        if name == "depth_guidance":
            depth = self.params["depth"]
            return {"setpoint": np.array([depth, self.heading, self.params["speed"], 0.0]),
                    "goal_error": np.array([abs(p[2] - depth)])}
        if isinstance(self.kind, StationGuidance):
            return self._station(p, yaw)
        return self._los(p)

    def _station(self, p: np.ndarray, yaw: float) -> dict[str, Any]:
        prm = self.params
        error = np.array([prm["x"] - p[0], prm["y"] - p[1]])
        world = prm["gain"] * error
        norm = float(np.linalg.norm(world))
        if norm > prm["max_speed"]:
            world *= prm["max_speed"] / norm
        c, s = math.cos(yaw), math.sin(yaw)
        u, v = c * world[0] + s * world[1], -s * world[0] + c * world[1]
        distance = math.hypot(float(np.linalg.norm(error)), p[2] - prm["depth"])
        return {"setpoint": np.array([prm["depth"], self.heading, u, v]),
                "goal_error": np.array([distance])}

    def _los(self, p: np.ndarray) -> dict[str, Any]:
        prm, points = self.params, self.points
        here = (float(p[0]), float(p[1]))
        if self.index is None:  # start (or resume) at the nearest waypoint
            self.index = int(np.argmin([math.dist(here, q) for q in points]))
            self.start = here
        last = len(points) - 1
        while self.index < last and math.dist(here, points[self.index]) < prm["radius"]:
            self.start = points[self.index]
            self.index += 1
        a, b = np.array(self.start), np.array(points[self.index])
        leg = b - a
        length = float(np.linalg.norm(leg))
        if length < 1e-6:
            heading = math.atan2(b[1] - here[1], b[0] - here[0])
        else:
            t = leg / length
            d = np.array(here) - a
            cross = float(t[0] * d[1] - t[1] * d[0])
            heading = math.atan2(t[1], t[0]) - math.atan(cross / prm["lookahead"])
        to_go = math.dist(here, points[self.index])
        speed = prm["speed"]
        goal = FAR_M
        if self.index == last:
            speed = min(speed, 0.25 * to_go + 0.1)
            goal = math.hypot(to_go, float(p[2]) - prm["depth"])
        return {"setpoint": np.array([prm["depth"], heading, speed, 0.0]),
                "goal_error": np.array([goal])}


_GAINS = (
    ("kp_depth", 20.0, "depth stiffness [N/m]"), ("kd_depth", 80.0, "depth damping [N·s/m]"),
    ("ki_depth", 2.0, "depth integral gain [N/(m·s)]"),
    ("max_integral", 20.0, "bound of the depth integral term [N]"),
    ("max_heave", 70.0, "bound of the heave force [N]"),
    ("kp_pitch", 100.0, "pitch stiffness [N·m/rad]"),
    ("kd_pitch", 60.0, "pitch damping [N·m·s/rad]"),
    ("kp_heading", 80.0, "heading stiffness [N·m/rad]"),
    ("kd_heading", 120.0, "heading damping [N·m·s/rad]"),
    ("k_speed", 60.0, "speed gain [N·s/m]"),
    ("drag_coeff", 14.9, "surge drag feed-forward [N·s²/m²]"),
)


class Autopilot(ModuleKind):
    """Depth, pitch, heading and speed loops and thruster allocation (module docstring)."""

    name = "auv_autopilot"
    summary = "AUV control law: depth, pitch, heading, speed loops + thruster allocation"
    ports = (PortSpec("setpoint", "in", "vector", 4, True, "depth, heading, u, v"),
             PortSpec("depth", "in", "float", None, True, "depth [m]"),
             PortSpec("attitude", "in", "vector", 3, True, "roll, pitch, yaw [rad]"),
             PortSpec("velocity", "in", "vector", 6, True, "u, v, w [m/s], p, q, r [rad/s]"),
             PortSpec("tau", "out", "vector", 5, True, "thruster forces [N]"))
    params = tuple(ParamSpec(name, "float", value, doc, 0.0) for name, value, doc in _GAINS)
    default_timing = Timing.from_ms(50.0, 1.0)
    c_implementation = AUTOPILOT_C

    def _instantiate(self, values: dict[str, Any], context: Any) -> ModuleInstance:
        return _AutopilotInstance(self, values, self.ports)


class _AutopilotInstance(ModuleInstance):
    def init(self) -> None:
        super().init()
        self.integral = 0.0
        self.last_t = None

    def compute(self, t_s: float, inputs: Mapping[str, Any]) -> dict[str, Any]:
        values = [inputs.get(p) for p in ("setpoint", "depth", "attitude", "velocity")]
        if any(v is None for v in values):
            return {}
        setpoint, depth, attitude, velocity = (np.asarray(v, dtype=float) for v in values)
        depth = _scalar(depth)
        dt = 0.0 if self.last_t is None else t_s - self.last_t
        self.last_t = t_s
        heave = self._heave(setpoint[0], depth, attitude, velocity, dt)
        prm = self.params
        pitch = -prm["kp_pitch"] * attitude[1] - prm["kd_pitch"] * velocity[4]
        yaw = prm["kp_heading"] * wrap(setpoint[1] - attitude[2]) - prm["kd_heading"] * velocity[5]
        surge = prm["k_speed"] * (setpoint[2] - velocity[0]) + \
            prm["drag_coeff"] * setpoint[2] * abs(setpoint[2])
        sway = prm["k_speed"] * (setpoint[3] - velocity[1])
        return {"tau": allocate(surge, heave, pitch, sway, yaw)}

    def _heave(self, target: float, depth: float, attitude: np.ndarray,
               velocity: np.ndarray, dt: float) -> float:
        """Heave force [N] (body z ≈ world up) from the depth loop."""
        prm = self.params
        roll, pitch = attitude[0], attitude[1]
        # world vertical velocity from the body velocity (z component of R v)
        w_up = (-math.sin(pitch) * velocity[0] + math.cos(pitch) * math.sin(roll) * velocity[1]
                + math.cos(pitch) * math.cos(roll) * velocity[2])
        error = depth - target
        bound = prm["max_integral"]
        self.integral = min(bound, max(-bound, self.integral + prm["ki_depth"] * error * dt))
        force = prm["kp_depth"] * error - prm["kd_depth"] * w_up + self.integral
        return min(prm["max_heave"], max(-prm["max_heave"], force))


def allocate(surge: float, heave: float, pitch: float, sway: float, yaw: float) -> np.ndarray:
    """Thruster forces [N] for the body force/moment demand, each clamped to its limit."""
    arm = THRUSTER_ARM_M
    forces = np.array([surge, (heave - pitch / arm) / 2.0, (heave + pitch / arm) / 2.0,
                       (sway + yaw / arm) / 2.0, (sway - yaw / arm) / 2.0])
    return np.clip(forces, -THRUST_LIMITS_N, THRUST_LIMITS_N)


MODULE_KINDS = (DepthGuidance(), LosGuidance(), LawnmowerGuidance(), StationGuidance(),
                WaypointGuidance(), HoldGuidance(), Autopilot())
