"""A robot's idle behaviour: what holds its plant while no Module-Task drives it.

A plant is *idle* from the start of a run until the first actuator write, and again from the
instant the last active Module-Task writing its actuators is killed until the next write
(between Robot-Tasks, after the last one, and from a task's start until its first command).
While idle, :class:`IdleHold` sets the actuator command before every integration step
according to the robot type's :class:`~orccad_app.control.robot.IdleBehaviour`:

- ``free``: zero command (the robot moves under gravity);
- ``brakes``: the joints are locked at the idle position (zero velocity, no command);
- ``hold``: gravity and Coriolis compensation (MuJoCo's bias force ``qfrc_bias`` of the last
  step) plus a PD law at the idle position, ``kp`` [N·m/rad], ``kv`` [N·m·s/rad], clamped to
  the torque limits.

The plant announces each change as a signal: ``ROBOT.idle`` (value: the behaviour's name)
when it goes idle and ``ROBOT.driven`` at the first write after it (docs/robot-tasks.md,
*Idle behaviour*); traces record both.
"""

from __future__ import annotations

import mujoco
import numpy as np

from orccad_app.control.robot import IdleBehaviour
from orccad_app.diagnostics import OrccadError

__all__ = ["IdleHold", "IdleBehaviour"]


class IdleHold:
    """The idle behaviour of one plant.

    :param behaviour: what holds the robot.
    :param model: the plant's MuJoCo model (``brakes`` and ``hold`` need one actuator per
        degree of freedom, in joint order).
    :param low: lower torque limits [N·m]; :param high: upper ones.
    :param kp: the holding law's stiffness [N·m/rad]; :param kv: its damping [N·m·s/rad].
    """

    def __init__(self, behaviour: IdleBehaviour, model: mujoco.MjModel, low: np.ndarray,
                 high: np.ndarray, kp: float = 400.0, kv: float = 40.0) -> None:
        if behaviour is not IdleBehaviour.FREE and (model.nu != model.nv or model.nq != model.nv):
            raise OrccadError(f"idle behaviour '{behaviour.value}' needs one actuator per "
                              f"joint (model has {model.nu} actuators, {model.nv} dofs)")
        self.behaviour = behaviour
        self.kp = kp
        self.kv = kv
        self._low = low
        self._high = high
        self._q = np.zeros(model.nq)

    def engage(self, data: mujoco.MjData) -> None:
        """The plant goes idle now: remember the position to hold."""
        self._q = data.qpos.copy()
        if self.behaviour is IdleBehaviour.BRAKES:
            data.qvel[:] = 0.0
        if self.behaviour is not IdleBehaviour.HOLD:
            data.ctrl[:] = 0.0
        else:
            self.before_step(data)

    def before_step(self, data: mujoco.MjData) -> None:
        """Set the command (or lock the joints) for the next integration step."""
        behaviour = self.behaviour
        if behaviour is IdleBehaviour.HOLD:
            tau = data.qfrc_bias + self.kp * (self._q - data.qpos) - self.kv * data.qvel
            data.ctrl[:] = np.clip(tau, self._low, self._high)
        elif behaviour is IdleBehaviour.BRAKES:
            data.qpos[:] = self._q
            data.qvel[:] = 0.0
