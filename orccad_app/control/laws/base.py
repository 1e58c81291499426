r"""The control law of RR-1801 eq. 5, shared by every law of the library.

.. math::

    \Gamma = -\hat M \hat J^{-1} \left(K_p e + K_v \dot e + K_i \int e\,dt\right)
             + \hat N - \hat M \hat J^{-1} \hat f

with :math:`\dot e = \hat J \dot q + \partial \hat e/\partial t` (eq. 2). Eq. 5 is the case
:math:`K_v = kG`, :math:`K_p = k\mu G D`; PID (eq. 8) is :math:`\hat M = I`,
:math:`\hat N = 0`, :math:`\hat f = 0`; computed torque uses the Pinocchio model. The
torque then goes through the robot's actuator constraint; the integral uses conditional
integration (anti-windup): a component of :math:`\int e` stops growing while growing it
would push a saturated joint further into saturation.

Sign convention: with :math:`e = q - q_d`, the feedback is negative. RR-1801 eq. 8 writes
the PID without the minus sign, its gains being understood as negative.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from orccad_app.control.errors import DimensionMismatch
from orccad_app.control.models import DynamicsModel, IdentityModel, PinocchioModel, perturbed_model
from orccad_app.control.params import ParamSpec, resolve_params
from orccad_app.control.task_functions import TaskFunction, TaskState
from orccad_app.control.trajectories import Sample
from orccad_app.control.laws.output import LawOutput

if TYPE_CHECKING:
    from orccad_app.control.robot import RobotType

__all__ = ["LawOutput", "Gains", "ControlLaw", "build_model"]


@dataclass(frozen=True)
class Gains:
    """``(m, m)`` matrices :math:`K_p`, :math:`K_v`, :math:`K_i` of the scheme."""

    kp: np.ndarray
    kv: np.ndarray
    ki: np.ndarray


def build_model(name: str, robot: RobotType, perturbation: float = 0.1,
                seed: int = 0) -> DynamicsModel:
    """The dynamic model ``identity``, ``pinocchio`` or ``perturbed`` of ``robot``."""
    if name == "identity":
        return IdentityModel(robot.dof)
    if name == "pinocchio":
        return PinocchioModel(robot.pinocchio_model())
    return perturbed_model(robot.pinocchio_model(), perturbation, seed)


class ControlLaw(ABC):
    """A control law for one robot and task function, with its integral state.

    Subclasses declare :attr:`PARAMS` and implement :meth:`_configure` (gains, model and
    feed-forward from :attr:`params`). :meth:`command` is called once per control period.
    """

    name: str = "law"
    PARAMS: tuple[ParamSpec, ...] = ()

    def __init__(self, params: Mapping[str, Any], robot: RobotType,
                 task_function: TaskFunction):
        if task_function.dim != robot.dof:
            raise DimensionMismatch(
                f"{self.name}: dim e = {task_function.dim} (task function "
                f"{task_function.name!r}) must equal dim q = {robot.dof} (robot {robot.name!r})")
        self.robot = robot
        self.task_function = task_function
        self.constraint = robot.actuator_constraint
        self.params = dict(params)
        self.model: DynamicsModel = IdentityModel(robot.dof)
        self.gains = Gains(*(np.zeros((robot.dof, robot.dof)),) * 3)
        self.feedforward = False
        self._configure()
        self._prepare()
        self.reset()

    @abstractmethod
    def _configure(self) -> None:
        """Set :attr:`gains`, :attr:`model` and :attr:`feedforward` from :attr:`params`."""

    # The integral and the saturation directions: arrays, which the lean path may hold as
    # lists of floats between its calls (materialized at the first read).
    _integral_list: list[float] | None = None
    _sat_list: list[float] | None = None

    @property
    def integral(self) -> np.ndarray:
        """:math:`\\int e\\,dt` so far (per task-error component)."""
        if self._integral_list is not None:
            self._integral_array = np.array(self._integral_list)
            self._integral_list = None
        return self._integral_array

    @integral.setter
    def integral(self, value: np.ndarray) -> None:
        self._integral_array = value
        self._integral_list = None

    @property
    def _sat_dir(self) -> np.ndarray:
        """Per joint, the sign of the last saturation (``tau_unsat - tau``)."""
        if self._sat_list is not None:
            self._sat_array = np.array(self._sat_list)
            self._sat_list = None
        return self._sat_array

    @_sat_dir.setter
    def _sat_dir(self, value: np.ndarray) -> None:
        self._sat_array = value
        self._sat_list = None

    def reset(self) -> None:
        """Forget the integral and the last sample time (at each task activation)."""
        self.integral = np.zeros(self.task_function.dim)
        self._t_prev: float | None = None
        self._sat_dir = np.zeros(self.robot.dof)

    def set_param(self, name: str, value: Any) -> None:
        """Change one parameter (type-1 exception), validated; the integral is kept."""
        values = resolve_params(self.name, self.PARAMS, {**self.params, name: value})
        old = self.params
        self.params = values
        try:
            self._configure()
        except Exception:
            self.params = old
            raise
        self._prepare()

    def _prepare(self) -> None:
        """Precompute what :meth:`command` needs at each call (after :meth:`_configure`).

        The lean path (:mod:`.fast`) serves joint tracking with diagonal gains and an
        identity or Pinocchio model and constant torque bounds; it does the same floating-point
        operations as the general path, so its torques are bit-identical.
        """
        from orccad_app.control.laws.fast import lean_path

        self._lean = lean_path(self)

    def command(self, t_s: float, q: Any, qdot: Any, reference: Sample) -> LawOutput:
        """Torque at time ``t_s`` [s] for joint state ``q`` [rad], ``qdot`` [rad/s]."""
        if self._lean is not None:
            out = self._lean.command(self, t_s, q, qdot, reference)
            if out is not None:
                return out
        q = np.asarray(q, dtype=float)
        qdot = np.asarray(qdot, dtype=float)
        state = self.task_function.evaluate(q, qdot, reference)
        mass = self.model.mass_matrix(q)
        effect = mass @ state.jacobian_inv
        self._integrate(state, effect, t_s)
        gains = self.gains
        feedback = gains.kp @ state.e + gains.kv @ state.e_dot + gains.ki @ self.integral
        tau_unsat = -effect @ feedback + self.model.nonlinear_effects(q, qdot)
        if self.feedforward:
            tau_unsat = tau_unsat - effect @ state.f
        tau, saturated = self.constraint.apply(tau_unsat, qdot)
        self._sat_dir = np.sign(tau_unsat - tau)
        return LawOutput(tau=tau, tau_unsat=tau_unsat, saturated=saturated, e=state.e)

    def _integrate(self, state: TaskState, effect: np.ndarray, t_s: float) -> None:
        dt = 0.0 if self._t_prev is None else max(t_s - self._t_prev, 0.0)
        self._t_prev = t_s
        if dt == 0.0 or not np.any(self.gains.ki):
            return
        delta = state.e * dt
        if self.params.get("anti_windup", True) and np.any(self._sat_dir):
            push = -(effect @ self.gains.ki) * delta[None, :] * self._sat_dir[:, None] > 0
            delta = np.where(push[self._sat_dir != 0].any(axis=0), 0.0, delta)
        self.integral = self.integral + delta
