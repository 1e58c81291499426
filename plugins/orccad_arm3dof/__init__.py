"""Built-in plugin ``orccad_arm3dof``: the 3-DOF direct-drive arm of RR-1801 §7.1.

The model is ``robots/arm3dof.xml`` at the root of the repository. This package ships it
as ``orccad_arm3dof/arm3dof.xml`` (a symbolic link in the source tree, a copy in a built
wheel), so the plugin, the tests and MuJoCo all read the same file.

In a plan::

    robot arm : arm3dof;       // ports arm.q [rad], arm.qdot [rad/s] (sensors), arm.tau [N·m]
    robot arm : arm3dof(noise_std = 1e-4, quantization = 1e-5);   // noisy, quantized encoders

Sensor parameters (:data:`ARM_SENSOR_PARAMS`, all 0 by default: ideal sensors): ``noise_std``
[rad] and ``qdot_noise_std`` [rad/s], the standard deviations of the Gaussian measurement noise
on ``q`` and ``qdot`` (drawn from the run's seed), and ``quantization`` [rad], the encoders'
resolution on ``q``.
"""

from __future__ import annotations

from pathlib import Path

from orccad_app.plugin_api import (
    IdleBehaviour,
    RobotType,
    SensorParam,
    SensorSetting,
    hookimpl,
)

__all__ = ["MJCF_PATH", "ARM3DOF", "ARM_SENSOR_PARAMS", "orccad_register_robot_types"]



def _mjcf_path() -> Path:
    """The packaged file, or the repository's when a checkout could not make the symbolic
    link (it is then a small text file holding the link's target)."""
    packaged = Path(__file__).with_name("arm3dof.xml")
    if packaged.read_bytes().lstrip().startswith(b"<"):
        return packaged
    return Path(__file__).resolve().parents[2] / "robots" / "arm3dof.xml"


#: The arm's MJCF file (resolves to ``robots/arm3dof.xml`` in a source checkout).
MJCF_PATH = _mjcf_path()

#: Measurement noise and encoder quantization, settable from a mission or ``--set arm.NAME=V``.
ARM_SENSOR_PARAMS = (
    SensorParam("noise_std", ("q",), SensorSetting.NOISE_STD, 0.0, "[rad]",
                "joint position measurement noise (standard deviation)", maximum=0.1),
    SensorParam("qdot_noise_std", ("qdot",), SensorSetting.NOISE_STD, 0.0, "[rad/s]",
                "joint velocity measurement noise (standard deviation)", maximum=10.0),
    SensorParam("quantization", ("q",), SensorSetting.QUANTIZATION, 0.0, "[rad]",
                "encoder resolution: q is rounded to a multiple of it (0: none)", maximum=0.1),
)

#: The robot type: 3 joints j1 (waist), j2 (shoulder), j3 (elbow), end effector site.
ARM3DOF = RobotType.from_mjcf(
    "arm3dof", MJCF_PATH,
    summary="3-DOF direct-drive arm of RR-1801 §7.1 (waist, shoulder, elbow)",
    sensor_params=ARM_SENSOR_PARAMS,
    idle=IdleBehaviour.HOLD)  # gravity compensation at the last position between tasks


@hookimpl
def orccad_register_robot_types(register):
    """The ``arm3dof`` robot type."""
    register(ARM3DOF)
