r"""The generic control scheme of RR-1801 eq. 5 and computed torque.

:class:`GenericScheme` is eq. 5 with an optional integral term:

.. math::

    \Gamma = -k \hat M \hat J^{-1} G (\mu D e + \dot e) - k_i \hat M \hat J^{-1} G D \int e\,dt
             + \hat N - \hat M \hat J^{-1} \hat f

``k`` and ``mu`` positive scalars, ``G`` and ``D`` positive matrices (scalar, diagonal or
full), models ``identity`` (:math:`\hat M = I, \hat N = 0`), ``pinocchio`` (from the
robot's MJCF) or ``perturbed`` (masses and inertias off by up to ``perturbation``).
``feedforward`` (default: on unless the model is ``identity``) includes :math:`\hat f`.

:class:`ComputedTorque` is the scheme with the Pinocchio model and :math:`G = D = I`,
written with joint gains:
:math:`\Gamma = \hat M \hat J^{-1} (-k_p e - k_v \dot e - \hat f) + \hat N`, i.e. for joint
tracking :math:`\hat M (\ddot q_d - k_p e - k_v \dot e) + \hat N`.
"""

from __future__ import annotations

from orccad_app.control.laws.base import ControlLaw, Gains, build_model
from orccad_app.control.laws.gains import adjusting_matrix, gain_matrix
from orccad_app.control.models import MODEL_NAMES
from orccad_app.control.params import REQUIRED, ParamSpec

__all__ = ["GenericScheme", "ComputedTorque"]

_MODEL_PARAMS = (
    ParamSpec("perturbation", "float", 0.1, "relative model error of 'perturbed' [-]", 0.0),
    ParamSpec("seed", "int", 0, "random seed of 'perturbed'"),
)


class GenericScheme(ControlLaw):
    """Eq. 5; see the module docstring for the parameters."""

    name = "generic"
    PARAMS = (
        ParamSpec("k", "float", REQUIRED, "velocity gain [1/s]", 0.0, True),
        ParamSpec("mu", "float", REQUIRED, "position/velocity gain ratio [1/s]", 0.0, True),
        ParamSpec("G", "matrix", 1.0, "positive adjusting matrix"),
        ParamSpec("D", "matrix", 1.0, "positive adjusting matrix"),
        ParamSpec("ki", "float", 0.0, "integral gain [1/s²]", 0.0),
        ParamSpec("model", "string", "pinocchio", "M̂, N̂ model", choices=MODEL_NAMES),
        ParamSpec("feedforward", "bool", None, "include f̂ (default: unless identity)"),
    ) + _MODEL_PARAMS + (
        ParamSpec("anti_windup", "bool", True, "conditional integration under saturation"),)

    def _configure(self) -> None:
        p, dim = self.params, self.task_function.dim
        g = adjusting_matrix(self.name, "G", p["G"], dim)
        d = adjusting_matrix(self.name, "D", p["D"], dim)
        self.gains = Gains(kp=p["k"] * p["mu"] * g @ d, kv=p["k"] * g, ki=p["ki"] * g @ d)
        self.model = build_model(p["model"], self.robot, p["perturbation"], p["seed"])
        feedforward = p["feedforward"]
        self.feedforward = p["model"] != "identity" if feedforward is None else feedforward


class ComputedTorque(ControlLaw):
    """Computed torque: ``kp`` [1/s²], ``kv`` [1/s] on the decoupled error dynamics."""

    name = "computed_torque"
    PARAMS = (
        ParamSpec("kp", "float|vector", 400.0, "position gain [1/s²]", 0.0, True),
        ParamSpec("kv", "float|vector", 40.0, "velocity gain [1/s]", 0.0, True),
        ParamSpec("model", "string", "pinocchio", "M̂, N̂ model", choices=MODEL_NAMES),
    ) + _MODEL_PARAMS

    def _configure(self) -> None:
        p, dim = self.params, self.task_function.dim
        self.gains = Gains(kp=gain_matrix(self.name, "kp", p["kp"], dim),
                           kv=gain_matrix(self.name, "kv", p["kv"], dim),
                           ki=gain_matrix(self.name, "ki", 0.0, dim, positive=False))
        self.model = build_model(p["model"], self.robot, p["perturbation"], p["seed"])
        self.feedforward = True
