"""The robot type ``auv``: a torpedo-like vehicle in ``robots/auv.xml`` plus its plant physics.

:class:`AuvRobotType` is a :class:`~orccad_app.control.RobotType` (a free-floating body, so it is
built by hand rather than by ``RobotType.from_mjcf``, which reads joint robots) that also
provides:

- ``plant_extension()``: the executive attaches :class:`~orccad_auv.physics.AuvPhysics` to the
  plant (buoyancy and restoring moment, battery, leak, the sensor ports, named faults);
- ``run_horizon_s``: ``orccad run`` without ``--until`` allows 900 s of simulated time (an AUV
  mission lasts minutes).

Ports: sensors ``depth``, ``attitude``, ``velocity``, ``position``, ``altitude``, ``battery``,
``leak``, ``gps`` (see :mod:`orccad_auv.physics`); actuator ``tau``: the five thruster forces
[N] (surge, vertical fore, vertical aft, lateral fore, lateral aft).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from orccad_app.plugin_api import (
    ActuatorConstraint,
    IdleBehaviour,
    ParamSpec,
    PortSpec,
    RobotPort,
    RobotType,
    SensorParam,
    SensorSetting,
    resolve_params,
)

from orccad_auv.physics import SENSOR_DIMS, AuvPhysics

__all__ = ["AuvRobotType", "AUV", "THRUSTERS", "MJCF_PATH", "AUV_PARAMS", "AUV_SENSOR_PARAMS"]

MJCF_PATH = Path(__file__).with_name("auv.xml")
THRUSTERS = ("surge", "vert_fore", "vert_aft", "lat_fore", "lat_aft")
THRUST_LIMITS_N = np.array([60.0, 40.0, 40.0, 30.0, 30.0])
THRUSTER_ARM_M = 0.6
"""Distance of the tunnel thrusters from the centre of gravity along the hull [m]."""

AUV_PARAMS = (
    ParamSpec("battery_wh", "float", 40.0, "battery capacity [Wh]", 0.0, True, maximum=10000.0),
    ParamSpec("volume_m3", "float", 0.0942, "displaced volume V [m³]", 0.0, True, maximum=1.0),
    ParamSpec("water_density", "float", 1025.0, "sea water density rho [kg/m³]", 900.0,
              maximum=1100.0),
    ParamSpec("cb_height_m", "float", 0.05, "centre of buoyancy above the CG [m]", 0.0,
              maximum=0.15),
    ParamSpec("hull_radius_m", "float", 0.15, "hull radius [m]", 0.0, True, maximum=1.0),
    ParamSpec("mass_kg", "float", None,
              "dry mass [kg] (default: the MJCF hull's 96 kg; the inertia scales with it)",
              50.0, maximum=150.0),
    ParamSpec("hotel_w", "float", 20.0, "hotel load (electronics) [W]", 0.0, maximum=1000.0),
    ParamSpec("thrust_coeff", "float", 0.5,
              "thruster power per N^1.5 [W/N^1.5] (ideal T^1.5/sqrt(2 rho A) of a 10 cm "
              "propeller is 0.25, at 50 % efficiency 0.5)", 0.0, maximum=10.0),
    ParamSpec("leak_rate_kg_s", "float", 0.01, "water intake of a leak [kg/s]", 0.0,
              maximum=10.0),
    ParamSpec("surface_damping", "float", 300.0,
              "heave damping while piercing the surface [N·s/m]", 0.0, maximum=10000.0),
    ParamSpec("gps_depth_m", "float", 0.4, "GPS antenna out of the water above [m]", 0.0,
              True, maximum=5.0),
)
"""Type parameters with their ranges (``robot auv : auv(cb_height_m = 0.08);``, or
``orccad run --set auv.cb_height_m=0.08``)."""

AUV_SENSOR_PARAMS = (
    SensorParam("depth_noise_std", ("depth",), SensorSetting.NOISE_STD, 0.02, "[m]",
                "pressure depth sensor noise (standard deviation)", maximum=5.0),
    SensorParam("attitude_noise_std", ("attitude",), SensorSetting.NOISE_STD, 0.002, "[rad]",
                "roll, pitch and heading noise (standard deviation)", maximum=0.5),
)
"""Sensor noise, settable like the type parameters (``robot auv : auv(depth_noise_std = 0.1);``
or ``--set auv.depth_noise_std=0.1``)."""

_UNITS = {"depth": "[m]", "attitude": "[rad]", "velocity": "[m/s, rad/s]", "position": "[m]",
          "altitude": "[m]", "battery": "[%]", "leak": "[0/1]", "gps": "[0/1]"}
_NOISE = {"depth": 0.02, "attitude": 0.002, "velocity": 0.01, "position": 0.05,
          "altitude": 0.05}
_DOCS = {"depth": "depth of the CG (pressure) [m]",
         "attitude": "roll, pitch, yaw [rad]",
         "velocity": "body u, v, w [m/s] (DVL) and p, q, r [rad/s] (gyro)",
         "position": "navigation estimate x, y [m] and depth [m]",
         "altitude": "height above the seabed [m]",
         "battery": "battery charge [%]",
         "leak": "leak detector, 1.0 when wet",
         "gps": "GPS fix available, 1.0 above water"}


@dataclass(frozen=True, eq=False)
class AuvRobotType(RobotType):
    """A robot type with a plant extension; see the module docstring."""

    run_horizon_s = 900.0
    """Default simulated-time limit of ``orccad run`` for missions on this robot [s]."""

    def physics_params(self) -> dict:
        """The type parameters with their defaults filled in."""
        return resolve_params(self.name, self.params, dict(self.param_values))

    def plant_extension(self) -> AuvPhysics:
        """A fresh :class:`AuvPhysics` for one run's plant."""
        return AuvPhysics(self.physics_params())


def _sensor(port: str) -> RobotPort:
    dim = SENSOR_DIMS[port]
    if dim:
        spec = PortSpec(port, "out", "vector", dim, doc=_DOCS[port])
        names = tuple(f"{port}[{i}]" for i in range(dim))
    else:
        spec = PortSpec(port, "out", "float", doc=_DOCS[port])
        names = (port,)
    return RobotPort(spec, _UNITS[port], names, noise_std=_NOISE.get(port, 0.0))


def make_auv() -> AuvRobotType:
    """The ``auv`` robot type."""
    tau = RobotPort(PortSpec("tau", "in", "vector", len(THRUSTERS),
                             doc="thruster forces [N]: " + ", ".join(THRUSTERS)),
                    "[N]", THRUSTERS)
    constraint = ActuatorConstraint(-THRUST_LIMITS_N, THRUST_LIMITS_N,
                                    np.full(len(THRUSTERS), np.inf), np.zeros(len(THRUSTERS)))
    return AuvRobotType(
        name="auv", summary="torpedo AUV, 2 m, 96 kg, 5 thrusters, seabed at 40 m",
        mjcf_path=MJCF_PATH.resolve(), resources=("hull",),
        sensors=tuple(_sensor(port) for port in SENSOR_DIMS), actuators=(tau,),
        actuator_constraint=constraint,
        joint_limits=(np.array([-np.inf]), np.array([np.inf])), end_effector=None,
        timestep_s=0.01, params=AUV_PARAMS, sensor_params=AUV_SENSOR_PARAMS,
        idle=IdleBehaviour.FREE)  # thrusters off while no task drives them


AUV = make_auv()
