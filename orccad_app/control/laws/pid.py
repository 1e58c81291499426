r"""PID in task space, RR-1801 eq. 8, with anti-windup.

.. math::

    \Gamma = -\hat J^{-1}\left(k_p e + k_v \dot e + k_i \int e\,dt\right)

It is eq. 5 with :math:`\hat M = I`, :math:`\hat N = 0`, no :math:`\hat f`, :math:`G = D = I`,
:math:`k = k_v` and :math:`\mu = k_p / k_v`; for joint tracking :math:`\hat J = I`.
Gains are scalars or one value per task component.
"""

from __future__ import annotations

from orccad_app.control.laws.base import ControlLaw, Gains
from orccad_app.control.laws.gains import gain_matrix
from orccad_app.control.models import IdentityModel
from orccad_app.control.params import ParamSpec

__all__ = ["PID"]


class PID(ControlLaw):
    """Eq. 8: ``kp`` [N·m/rad], ``kv`` [N·m·s/rad], ``ki`` [N·m/(rad·s)] (joint space)."""

    name = "pid"
    PARAMS = (
        ParamSpec("kp", "float|vector", 400.0, "proportional gain [N·m/rad]", 0.0, True),
        ParamSpec("kv", "float|vector", 40.0, "derivative gain [N·m·s/rad]", 0.0, True),
        ParamSpec("ki", "float|vector", 0.0, "integral gain [N·m/(rad·s)]", 0.0),
        ParamSpec("anti_windup", "bool", True, "conditional integration under saturation"),
    )

    def _configure(self) -> None:
        dim = self.task_function.dim
        self.gains = Gains(kp=gain_matrix(self.name, "kp", self.params["kp"], dim),
                           kv=gain_matrix(self.name, "kv", self.params["kv"], dim),
                           ki=gain_matrix(self.name, "ki", self.params["ki"], dim,
                                          positive=False))
        self.model = IdentityModel(self.robot.dof)
        self.feedforward = False
