"""A robot's MuJoCo plant with named accessors (the dm_control ``Physics`` idea).

:class:`RobotPhysics` reads sensor ports from ``sensordata`` and writes actuator ports
into a held command that :meth:`RobotPhysics.step` re-applies, through the robot's
:class:`~orccad_app.control.constraints.ActuatorConstraint`, at every integration step
(zero-order hold; the velocity-dependent bounds follow the motion between writes).
The first actuator port (``tau``) is the torque port; values are in joint order.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from orccad_app.control.errors import ControlError, DimensionMismatch
from orccad_app.control.robot import RobotType

__all__ = ["RobotPhysics"]


class RobotPhysics:
    """MuJoCo model and data of ``robot``, stepped with the held torque command."""

    def __init__(self, robot: RobotType, model: Any = None):
        import mujoco

        self._mujoco = mujoco
        self.robot = robot
        self.model = model if model is not None else robot.mujoco_model()
        self.data = mujoco.MjData(self.model)
        self._sensor_slices = {port.name: self._slices(port.mj_names) for port in robot.sensors}
        torque_port = robot.actuators[0]
        self._torque_port = torque_port.name
        self._torque_ids = np.array([
            mujoco.mj_name2id(self.model, mujoco.mjtObj.mjOBJ_ACTUATOR, n)
            for n in torque_port.mj_names])
        #: held torque command [N·m], in the order of the torque port (joint order)
        self.command = np.zeros(torque_port.dim)

    def _slices(self, names: tuple[str, ...]) -> np.ndarray:
        mujoco = self._mujoco
        ids = [mujoco.mj_name2id(self.model, mujoco.mjtObj.mjOBJ_SENSOR, n) for n in names]
        return np.array([self.model.sensor_adr[i] for i in ids])

    @property
    def time(self) -> float:
        """Simulated time [s]."""
        return float(self.data.time)

    def joint_positions(self) -> np.ndarray:
        """``q`` [rad] (exact state, not the sensor)."""
        return self.data.qpos.copy()

    def joint_velocities(self) -> np.ndarray:
        """``qdot`` [rad/s] (exact state, not the sensor)."""
        return self.data.qvel.copy()

    def set_state(self, q: Any, qdot: Any = None, time: float = 0.0) -> None:
        """Reset to ``q`` [rad], ``qdot`` [rad/s] at ``time`` [s]; sensors refreshed."""
        self._mujoco.mj_resetData(self.model, self.data)
        self.data.qpos[:] = np.asarray(q, dtype=float)
        self.data.qvel[:] = 0.0 if qdot is None else np.asarray(qdot, dtype=float)
        self.data.time = time
        self.command[:] = 0.0
        self._mujoco.mj_forward(self.model, self.data)

    def read(self, port: str) -> np.ndarray:
        """Current value of the sensor port ``port`` (e.g. ``"q"``)."""
        self.robot.port(port)
        return self.data.sensordata[self._sensor_slices[port]].copy()

    def write(self, port: str, value: Any) -> None:
        """Hold ``value`` on the torque port ``port`` (``"tau"`` [N·m])."""
        spec = self.robot.port(port).spec
        if port != self._torque_port:
            raise ControlError(f"port {port!r} is not the robot's actuator port "
                                    f"{self._torque_port!r}")
        value = np.asarray(value, dtype=float)
        if value.shape != (spec.dim,):
            raise DimensionMismatch(f"port {port!r} expects {spec.dim} values, "
                                    f"got shape {value.shape}")
        self.command[:] = value

    def applied_torque(self) -> np.ndarray:
        """The torque the constraint lets through at the current velocity [N·m]."""
        tau, _ = self.robot.actuator_constraint.apply(self.command, self.data.qvel)
        return tau

    def step(self, n: int = 1) -> None:
        """Advance ``n`` integration steps of ``timestep_s`` with the held command."""
        for _ in range(n):
            self.data.ctrl[self._torque_ids] = self.applied_torque()
            self._mujoco.mj_step(self.model, self.data)
