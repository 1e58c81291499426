"""Control laws: the generic scheme of eq. 5, PID (eq. 8), computed torque."""

from orccad_app.control.laws.base import ControlLaw, Gains, LawOutput, build_model
from orccad_app.control.laws.pid import PID, PID_KIND
from orccad_app.control.laws.scheme import (
    COMPUTED_TORQUE_KIND,
    GENERIC_KIND,
    ComputedTorque,
    GenericScheme,
)

__all__ = [
    "ControlLaw",
    "Gains",
    "LawOutput",
    "build_model",
    "PID",
    "GenericScheme",
    "ComputedTorque",
    "PID_KIND",
    "GENERIC_KIND",
    "COMPUTED_TORQUE_KIND",
    "LAW_KINDS",
]

#: The built-in law kinds, registered by the ``orccad_control`` plugin.
LAW_KINDS = (PID_KIND, GENERIC_KIND, COMPUTED_TORQUE_KIND)
