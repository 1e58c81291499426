"""Control laws: the generic scheme of eq. 5, PID (eq. 8), computed torque."""

from orccad_app.control.laws.base import ControlLaw, Gains, LawOutput, build_model
from orccad_app.control.laws.pid import PID
from orccad_app.control.laws.scheme import ComputedTorque, GenericScheme

__all__ = [
    "ControlLaw",
    "Gains",
    "LawOutput",
    "build_model",
    "PID",
    "GenericScheme",
    "ComputedTorque",
]
