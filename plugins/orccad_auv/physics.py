"""The AUV's plant extension: hydrostatics, battery, leak, sensors and faults.

MuJoCo integrates the rigid body, gravity, the thrusters and the ellipsoid fluid drag of
``robots/auv.xml``. It has no hydrostatics, so :class:`AuvPhysics` applies each step:

- **buoyancy** ``B = rho g V f`` upward [N] at the centre of buoyancy (``cb_height_m`` above the
  centre of gravity, in the body frame), ``f`` the submerged fraction (linear over the hull's
  diameter around the surface); its moment about the centre of gravity is the restoring moment
  ``B · cb_height_m · sin(roll)`` that rights the vehicle;
- **surface damping**: while the hull pierces the surface, a heave damping
  ``surface_damping`` [N·s/m] stands for the energy radiated by the waves it makes;
- **leak**: after the ``leak`` fault, water comes in at ``leak_rate_kg_s``: an extra weight.

It integrates the **battery** energy: hotel load ``hotel_w`` plus ``thrust_coeff · |F|^1.5``
per thruster [W] (the ideal propeller power grows as thrust^1.5).

Sensor ports (values at the read instant; noise is the robot type's per-port ``noise_std``):

====================  ======  ==================================================
``depth``             float   depth of the centre of gravity [m] (pressure)
``attitude``          vector  roll, pitch, yaw [rad] (ZYX Euler angles)
``velocity``          vector  body u, v, w [m/s] (DVL), p, q, r [rad/s] (gyro)
``position``          vector  x, y [m] and depth [m] (navigation estimate)
``altitude``          float   height above the seabed [m] (altimeter)
``battery``           float   charge left [%]
``leak``              float   1.0 when the leak detector is wet, else 0.0
``gps``               float   1.0 when the GPS antenna is above water, else 0.0
====================  ======  ==================================================

Faults (``--inject auv.FAULT=VALUE@T``): ``battery`` (set the charge [%]), ``leak`` (1: water
comes in), ``gps_denied`` (1: no fix), ``thrust`` (efficiency of every thruster [0..1]),
``PORT_bias`` (add VALUE to every component of sensor PORT: depth [m], altitude [m],
attitude [rad], velocity [m/s, rad/s], position [m]) and ``PORT_stuck`` (1: the sensor keeps
its current value; 0: it recovers).
"""

from __future__ import annotations

import math
from typing import Any

import mujoco
import numpy as np

from orccad_app.plugin_api import FLAG, FaultRange, PlantExtension

__all__ = ["AuvPhysics", "SENSOR_DIMS", "G_MPS2"]

G_MPS2 = 9.81
SENSOR_DIMS = {"depth": 0, "attitude": 3, "velocity": 6, "position": 3, "altitude": 0,
               "battery": 0, "leak": 0, "gps": 0}
"""Sensor port -> dimension (0: a ``float`` port)."""
_BIASED = ("depth", "attitude", "velocity", "position", "altitude")


def euler_zyx(quat: np.ndarray) -> np.ndarray:
    """Roll, pitch, yaw [rad] of the unit quaternion ``quat`` (w, x, y, z)."""
    # Python floats: the same IEEE arithmetic as on numpy scalars, without their overhead
    w, x, y, z = quat.tolist() if isinstance(quat, np.ndarray) else quat
    roll = math.atan2(2.0 * (w * x + y * z), 1.0 - 2.0 * (x * x + y * y))
    pitch = math.asin(max(-1.0, min(1.0, 2.0 * (w * y - z * x))))
    yaw = math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))
    return np.array([roll, pitch, yaw])


class AuvPhysics(PlantExtension):
    """See the module docstring. ``params`` are the robot type's parameter values."""

    sensors = {port: max(dim, 1) for port, dim in SENSOR_DIMS.items()}
    fault_ranges = {"battery": FaultRange(0.0, 100.0), "leak": FLAG, "gps_denied": FLAG,
                    "thrust": FaultRange(0.0, 1.0),
                    **{f"{port}_bias": FaultRange(-1e3, 1e3) for port in _BIASED},
                    **{f"{port}_stuck": FLAG for port in SENSOR_DIMS}}
    faults = {"battery": "set the battery charge [%]",
              "leak": "1: the hull leaks (leak_rate_kg_s of water comes in)",
              "gps_denied": "1: no GPS fix even at the surface",
              "thrust": "efficiency of every thruster [0..1]",
              **{f"{port}_bias": f"add VALUE to sensor {port}" for port in _BIASED},
              **{f"{port}_stuck": f"1: sensor {port} keeps its value, 0: recovers"
                 for port in SENSOR_DIMS}}

    def __init__(self, params: dict[str, Any]) -> None:
        self.params = dict(params)
        self.energy_j = 0.0
        """Energy drawn from the battery [J]."""
        self.leaking = False
        self.water_kg = 0.0
        """Water taken in through the leak [kg]."""
        self.gps_denied = False
        self.efficiency = 1.0
        self.bias: dict[str, float] = {}
        self.stuck: dict[str, np.ndarray] = {}
        self.charge0_j = 3600.0 * float(self.params["battery_wh"])
        self.max_depth_m = 0.0
        """The deepest the centre of gravity has been [m]."""

    def bind(self, model: mujoco.MjModel, data: mujoco.MjData) -> None:
        self.model, self.data = model, data
        self.body = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, "hull")
        seabed = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_GEOM, "seabed")
        self.seabed_z_m = float(model.geom_pos[seabed][2])
        mass = self.params.get("mass_kg")
        if mass is not None:  # the type parameter: scale the hull's mass and inertia
            model.body_inertia[self.body] *= float(mass) / float(model.body_mass[self.body])
            model.body_mass[self.body] = float(mass)
        self.mass_kg = float(model.body_mass[self.body])
        self.gain = model.actuator_gear[:, 2].copy()
        p = self.params  # the parameters step() reads, once (rho g V as buoyancy_n groups it)
        self._constants = (float(p["hull_radius_m"]),
                           p["water_density"] * G_MPS2 * p["volume_m3"], p["surface_damping"],
                           float(p["cb_height_m"]), p["hotel_w"], p["thrust_coeff"],
                           p["leak_rate_kg_s"])
        # views into MuJoCo's state (same memory for the life of ``data``), read every step
        self._xpos, self._xmat = data.xpos[self.body], data.xmat[self.body]
        self._xfrc, self._qvel, self._ctrl = data.xfrc_applied[self.body], data.qvel, data.ctrl

    # -- physics ---------------------------------------------------------------------------

    def submerged_fraction(self) -> float:
        """Fraction of the hull's volume under water (linear over its diameter) [-]."""
        radius = float(self.params["hull_radius_m"])
        z = float(self.data.xpos[self.body][2])
        return min(1.0, max(0.0, (radius - z) / (2.0 * radius)))

    def buoyancy_n(self) -> float:
        """Buoyancy now [N]: rho g V times the submerged fraction."""
        p = self.params
        return p["water_density"] * G_MPS2 * p["volume_m3"] * self.submerged_fraction()

    def step(self, dt_s: float) -> None:
        # Plain float arithmetic on cached views of MuJoCo's arrays (this runs before every
        # integration step): the same IEEE operations, in the same order, as the numpy
        # expressions ``rot @ [0, 0, h]``, ``np.cross(arm, [0, 0, B])`` and
        # ``np.sum(np.abs(ctrl) ** 1.5)`` (a sequential sum for so few thrusters), so the
        # run is bit-identical; numpy's per-call overhead was most of a step.
        radius, rho_g_v, damping, height, hotel, thrust_coeff, leak_rate = self._constants
        z = float(self._xpos[2])
        if -z > self.max_depth_m:
            self.max_depth_m = -z
        fraction = min(1.0, max(0.0, (radius - z) / (2.0 * radius)))
        buoyancy = rho_g_v * fraction
        up = buoyancy - G_MPS2 * self.water_kg
        if 0.0 < fraction < 1.0:  # wave-making (radiation) damping
            up -= damping * float(self._qvel[2])
        r = self._xmat.tolist()
        arm0 = ((0.0 + r[0] * 0.0) + r[1] * 0.0) + r[2] * height
        arm1 = ((0.0 + r[3] * 0.0) + r[4] * 0.0) + r[5] * height
        arm2 = ((0.0 + r[6] * 0.0) + r[7] * 0.0) + r[8] * height
        xfrc = self._xfrc
        xfrc[0] = 0.0
        xfrc[1] = 0.0
        xfrc[2] = up
        xfrc[3] = arm1 * buoyancy - arm2 * 0.0
        xfrc[4] = arm2 * 0.0 - arm0 * buoyancy
        xfrc[5] = arm0 * 0.0 - arm1 * 0.0
        total = 0.0
        for index, command in enumerate(self._ctrl.tolist()):
            term = abs(command) ** 1.5
            total = term if index == 0 else total + term
        power = hotel + thrust_coeff * total * self.efficiency
        self.energy_j += power * dt_s
        if self.leaking:
            self.water_kg += leak_rate * dt_s

    # -- sensors ---------------------------------------------------------------------------

    def battery_percent(self) -> float:
        """Charge left [%]."""
        return max(0.0, 100.0 * (1.0 - self.energy_j / self.charge0_j))

    def true_value(self, port: str) -> np.ndarray:
        """The noiseless, fault-free value of sensor ``port``."""
        data, body = self.data, self.body
        pos = self._xpos.tolist()
        if port == "depth":
            return np.array(-pos[2])
        if port == "attitude":
            return euler_zyx(data.xquat[body])
        if port == "velocity":
            rot = self._xmat.reshape(3, 3)
            return np.concatenate([rot.T @ self._qvel[:3], self._qvel[3:6]])
        if port == "position":
            return np.array([pos[0], pos[1], -pos[2]])
        if port == "altitude":
            return np.array(pos[2] - self.seabed_z_m)
        if port == "battery":
            return np.array(self.battery_percent())
        if port == "leak":
            return np.array(float(self.leaking))
        if port == "gps":
            return np.array(float(-pos[2] < self.params["gps_depth_m"] and not self.gps_denied))
        raise KeyError(port)

    def read(self, port: str) -> np.ndarray:
        if port in self.stuck:
            return self.stuck[port].copy()
        return self.true_value(port) + self.bias.get(port, 0.0)

    # -- faults ----------------------------------------------------------------------------

    def inject(self, fault: str, value: Any) -> None:
        number = float(value) if value is not None else 1.0
        if fault == "battery":
            self.energy_j = self.charge0_j * (1.0 - min(100.0, max(0.0, number)) / 100.0)
        elif fault == "leak":
            self.leaking = number != 0.0
        elif fault == "gps_denied":
            self.gps_denied = number != 0.0
        elif fault == "thrust":  # the thrusters' gear: exact forces and moments
            self.efficiency = min(1.0, max(0.0, number))
            self.model.actuator_gear[:, 2] = self.gain * self.efficiency
        elif fault.endswith("_bias"):
            self.bias[fault[:-5]] = number
        elif fault.endswith("_stuck"):
            port = fault[:-6]
            if number != 0.0:
                self.stuck[port] = self.read(port)
            else:
                self.stuck.pop(port, None)
        else:
            raise KeyError(fault)
