"""The control library: task functions, trajectories, control laws, models, constraints.

RR-1801 §3.1: a Robot-Task's servo-control is a task function :math:`e(q, t)` regulated by
the generic scheme of eq. 5; PID (eq. 8) and computed torque are instances. Models come
from Pinocchio built from the same MJCF that MuJoCo simulates. Module kinds
(:mod:`.module`) cut the scheme into periodic Module-Tasks with typed ports.

Layering: this package imports neither the plugin host nor the executive; plugins
register its kinds (the built-in ``orccad_control`` plugin registers :mod:`.catalogue`).
Inside, imports form a chain: :mod:`.ports` (the port and timing vocabulary) and
:mod:`.params` at the bottom, then the trajectories, task functions and laws, then
:mod:`.kinds`, :mod:`.robot`, :mod:`.context` (:class:`ModuleContext`), :mod:`.module`
(Module-Task kinds), :mod:`.spec` and :mod:`.catalogue`. The closed-loop check without the
executive is :mod:`orccad_app.control.closed_loop`.
"""

from orccad_app.control.catalogue import (
    LAW_KINDS,
    MODULE_KINDS,
    TASK_FUNCTION_KINDS,
    TRAJECTORY_KINDS,
)
from orccad_app.control.constraints import ActuatorConstraint
from orccad_app.control.context import ModuleContext
from orccad_app.control.errors import ControlError, DimensionMismatch, InvalidParameter
from orccad_app.control.kinds import (
    ComponentKind,
    DefaultModule,
    LawKind,
    Spec,
    TaskFunctionKind,
    TrajectoryKind,
)
from orccad_app.control.laws import PID, ComputedTorque, ControlLaw, GenericScheme, LawOutput
from orccad_app.control.models import DynamicsModel, IdentityModel, PinocchioModel, perturbed_model
from orccad_app.control.module import ModuleInstance, ModuleKind
from orccad_app.control.module_kinds import ControlLawModule, TrajectoryModule
from orccad_app.control.params import REQUIRED, ParamSpec, resolve_params
from orccad_app.control.physics import RobotPhysics
from orccad_app.control.plant_extension import PlantExtension
from orccad_app.control.ports import PortDirection, PortSpec, Timing
from orccad_app.control.robot import RobotPort, RobotType
from orccad_app.control.spec import module_context, resolve
from orccad_app.control.task_functions import CartesianTracking, JointTracking, TaskFunction, TaskState
from orccad_app.control.trajectories import Constant, Cosine, MinimumJerk, Sample, Trajectory

__all__ = [
    "ActuatorConstraint",
    "CartesianTracking",
    "ComponentKind",
    "ComputedTorque",
    "Constant",
    "ControlError",
    "ControlLaw",
    "ControlLawModule",
    "DefaultModule",
    "Cosine",
    "DimensionMismatch",
    "DynamicsModel",
    "GenericScheme",
    "IdentityModel",
    "InvalidParameter",
    "JointTracking",
    "LAW_KINDS",
    "LawKind",
    "LawOutput",
    "MODULE_KINDS",
    "MinimumJerk",
    "ModuleContext",
    "ModuleInstance",
    "ModuleKind",
    "PID",
    "ParamSpec",
    "PinocchioModel",
    "PlantExtension",
    "PortDirection",
    "PortSpec",
    "REQUIRED",
    "RobotPhysics",
    "RobotPort",
    "RobotType",
    "Sample",
    "Spec",
    "TASK_FUNCTION_KINDS",
    "TRAJECTORY_KINDS",
    "TaskFunction",
    "TaskFunctionKind",
    "TaskState",
    "Timing",
    "Trajectory",
    "TrajectoryKind",
    "TrajectoryModule",
    "module_context",
    "perturbed_model",
    "resolve",
    "resolve_params",
]
