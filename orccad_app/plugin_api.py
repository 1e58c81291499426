"""The public API for plugin authors: the one module of ``orccad_app`` a plugin imports.

A plugin (docs/plugins.md) marks its hook implementations with :data:`hookimpl` and
registers objects built from the classes below: robot types (:class:`RobotType`, with its
sensor parameters :class:`SensorParam` and its extension points :meth:`RobotType.plant_extension` and :attr:`RobotType.run_horizon_s`),
component kinds (:class:`TrajectoryKind`, :class:`TaskFunctionKind`, :class:`LawKind`) and
Module-Task kinds (:class:`ModuleKind`, with their C for ``orccad sil``:
:class:`CImplementation`), declared with :class:`ParamSpec`, :class:`PortSpec`
and :class:`Timing`. Errors it raises are :class:`OrccadError` (or the control library's
subclasses: :class:`ControlError`, :class:`DimensionMismatch`, :class:`InvalidParameter`).

Everything else in ``orccad_app`` is internal and may change without notice; a test checks
that the built-in plugins (``plugins/``) import nothing else from the core.
"""

from orccad_app.control.c_implementation import CField, CFieldType, CImplementation, kind_header
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
    STANDARD_SCHEME,
    ComponentKind,
    DefaultModule,
    LawKind,
    TaskFunctionKind,
    TrajectoryKind,
)
from orccad_app.control.laws.base import ControlLaw, Gains, LawOutput
from orccad_app.control.laws.gains import adjusting_matrix, gain_matrix
from orccad_app.control.models import DynamicsModel, IdentityModel, PinocchioModel
from orccad_app.control.module import ModuleInstance, ModuleKind
from orccad_app.control.params import REQUIRED, ParamSpec, resolve_params
from orccad_app.control.plant_extension import FLAG, FaultRange, PlantExtension
from orccad_app.control.ports import PORT_TYPES, TASK_ERROR, PortDirection, PortSpec, Timing
from orccad_app.control.robot import (
    IdleBehaviour,
    RobotPort,
    RobotType,
    SensorParam,
    SensorSetting,
)
from orccad_app.control.task_functions import TaskFunction, TaskState
from orccad_app.control.trajectories import Sample, Trajectory
from orccad_app.diagnostics import OrccadError
from orccad_app.plugin_host.hookspecs import Register, hookimpl
from orccad_app.plugin_host.host import PluginHost

__all__ = [
    # hooks
    "hookimpl",
    "Register",
    "PluginHost",
    # robots
    "RobotType",
    "RobotPort",
    "IdleBehaviour",
    "SensorParam",
    "SensorSetting",
    "ActuatorConstraint",
    "PlantExtension",
    "FaultRange",
    "FLAG",
    # component kinds and what they build
    "ComponentKind",
    "TrajectoryKind",
    "Trajectory",
    "Sample",
    "TaskFunctionKind",
    "TaskFunction",
    "TaskState",
    "LawKind",
    "DefaultModule",
    "STANDARD_SCHEME",
    "ControlLaw",
    "Gains",
    "LawOutput",
    "gain_matrix",
    "adjusting_matrix",
    "DynamicsModel",
    "IdentityModel",
    "PinocchioModel",
    # Module-Tasks
    "ModuleKind",
    "CImplementation",
    "CField",
    "CFieldType",
    "kind_header",
    "ModuleInstance",
    "ModuleContext",
    "PortSpec",
    "PortDirection",
    "PORT_TYPES",
    "TASK_ERROR",
    "Timing",
    # parameters
    "ParamSpec",
    "REQUIRED",
    "resolve_params",
    # errors
    "OrccadError",
    "ControlError",
    "DimensionMismatch",
    "InvalidParameter",
    # the built-in catalogue (registered by the built-in orccad_control plugin)
    "TRAJECTORY_KINDS",
    "TASK_FUNCTION_KINDS",
    "LAW_KINDS",
    "MODULE_KINDS",
]
