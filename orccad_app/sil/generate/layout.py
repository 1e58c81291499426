"""The C layout of a Module-Task: which C kind runs it, its slots and its parameter vector.

A Python module instance (what the executive would run) is described to the C runtime
(``orccad_app/sil/c/orccad_mt.c`` and its kinds' files) by a :class:`CLayout`: the C kind, the
input and output ports in the Python kind's port order with their dimensions and types, and
the parameters as one vector of doubles whose offsets the C kind reads (the layouts are listed
in each kind's file: ``orccad_mt_trajectory.c``, ``orccad_mt_laws.c``); a plugin's kind
gives its own words to its own C (``ModuleKind.c_implementation``: the observers',
``plugins/orccad_observers/c_kinds.py``; the AUV's, ``plugins/orccad_auv/c_kinds.py``). The robot file's data a kind needs — joint
limits, the actuator constraint — goes into the vector too: the C code never reads the robot
file.

:func:`c_layout` refuses, with the module kind's name and the reason, a kind that has no C
implementation (:class:`NoCImplementation`): a plugin's kind whose plugin gives no C
(``ModuleKind.c_implementation``: then its C file is compiled in, :data:`CKind.PLUGIN`), a law
other than PID or computed torque, a model other than Pinocchio's (exact or perturbed), a task
function other than joint tracking, a vector longer than the runtime's slots.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from enum import IntEnum
from typing import Any

import numpy as np

from orccad_app.control.errors import ControlError
from orccad_app.diagnostics import OrccadError

__all__ = ["CKind", "CLayout", "CPort", "MAX_DIM", "MAX_PARAMS", "NoCImplementation",
           "c_layout", "kind_c", "same_word"]

MAX_DIM = 16
"""Components of a vector port in the C runtime (``ORC_MAX_DIM``)."""
MAX_PORTS = 8
MAX_PARAMS = 192
"""Doubles of parameters of one C Module-Task (``ORC_MAX_PARAMS``)."""


class CKind(IntEnum):
    """The C kinds of ``orccad_mt.h`` (``enum orc_kind``)."""

    TRAJ_COSINE = 1
    TRAJ_MIN_JERK = 2
    TRAJ_CONSTANT = 3
    LAW_PID = 10
    LAW_CT = 11
    MODEL_DYN = 12
    CT_FEEDBACK = 13
    PLUGIN = 100
    """A plugin kind's C (``ORC_PLUGIN_BASE``: the table numbers each plugin kind from it)."""


class NoCImplementation(OrccadError):
    """A Module-Task kind the C runtime cannot run (its name and the reason in the message)."""


@dataclass(frozen=True)
class CPort:
    """One slot: the Python port's name, its type and its number of components."""

    name: str
    type: str
    dim: int


@dataclass(frozen=True)
class CLayout:
    """How the C runtime runs one Module-Task instance (see the module docstring)."""

    kind: CKind
    inputs: tuple[CPort, ...]
    outputs: tuple[CPort, ...]
    params: tuple[float, ...]
    plugin: Any = None
    """For :attr:`CKind.PLUGIN`: the kind's
    :class:`~orccad_app.control.c_implementation.CImplementation`."""

    @property
    def input_doubles(self) -> int:
        """Doubles of a compute request: ``[present, v...]`` per input slot."""
        return sum(1 + port.dim for port in self.inputs)

    @property
    def output_doubles(self) -> int:
        """Doubles of a compute reply."""
        return sum(1 + port.dim for port in self.outputs)


def _ports(instance: Any, direction: str) -> tuple[CPort, ...]:
    ports = tuple(CPort(p.name, p.type, p.dim or 1) for p in instance.ports
                  if p.direction == direction)
    if len(ports) > MAX_PORTS:
        raise NoCImplementation(f"module kind {instance.kind.name!r}: {len(ports)} "
                                f"{direction}put ports, the C runtime has {MAX_PORTS} slots")
    for port in ports:
        if port.dim > MAX_DIM:
            raise NoCImplementation(f"module kind {instance.kind.name!r}: port {port.name!r} "
                                    f"has {port.dim} components, the C runtime {MAX_DIM}")
    return ports


def same_word(a: float, b: float) -> bool:
    """Two parameter words are the same double, bit for bit (``0.0`` and ``-0.0`` differ)."""
    return a == b and math.copysign(1.0, a) == math.copysign(1.0, b)


def _floats(values: Any) -> list[float]:
    return [float(v) for v in np.asarray(values, dtype=float).reshape(-1)]


def _trajectory(instance: Any) -> tuple[CKind, list[float]]:
    from orccad_app.control.task_functions.joint import JointTracking
    from orccad_app.control.trajectories.constant import Constant
    from orccad_app.control.trajectories.cosine import Cosine
    from orccad_app.control.trajectories.minimum_jerk import MinimumJerk

    task_function = instance.task_function
    if type(task_function) is not JointTracking:
        raise NoCImplementation(f"module kind 'trajectory': task function "
                                f"{task_function.name!r} has no C implementation (joint "
                                f"tracking only)")
    trajectory = task_function.trajectory
    dim = task_function.dim
    if type(trajectory) is Cosine:
        return CKind.TRAJ_COSINE, [dim, trajectory.omega, *_floats(trajectory.q0)]
    if type(trajectory) is MinimumJerk:
        start = trajectory.start
        return CKind.TRAJ_MIN_JERK, [dim, trajectory.duration, 0.0 if start is None else 1.0,
                                     *_floats(trajectory.goal),
                                     *(_floats(start) if start is not None else [0.0] * dim)]
    if type(trajectory) is Constant:
        value = trajectory.value
        return CKind.TRAJ_CONSTANT, [dim, 0.0 if value is None else 1.0,
                                     *(_floats(value) if value is not None else [0.0] * dim)]
    raise NoCImplementation(f"module kind 'trajectory': trajectory {trajectory.name!r} has no "
                            f"C implementation (cosine, min_jerk and constant have)")


def _constraint(constraint: Any) -> list[float]:
    return [*_floats(constraint.tau_min), *_floats(constraint.tau_max),
            *_floats(constraint.alpha), *_floats(constraint.beta)]


def _control_law(instance: Any) -> tuple[CKind, list[float]]:
    from orccad_app.control.laws.pid import PID
    from orccad_app.control.laws.scheme import ComputedTorque
    from orccad_app.control.task_functions.joint import JointTracking

    law = instance.law
    if type(law) is ComputedTorque and type(law.task_function) is JointTracking:
        return CKind.LAW_CT, [law.robot.dof, 1.0 if law.feedforward else 0.0,
                              *_diagonal("control_law", law.gains.kp),
                              *_diagonal("control_law", law.gains.kv),
                              *_constraint(law.constraint),
                              *_model_damping("control_law", law.model),
                              *_model_block("control_law", law.model)]
    if type(law) is not PID:
        raise NoCImplementation(f"module kind 'control_law': law {law.name!r} has no C "
                                f"implementation (pid and computed_torque have)")
    if type(law.task_function) is not JointTracking:
        raise NoCImplementation(f"module kind 'control_law': task function "
                                f"{law.task_function.name!r} has no C implementation "
                                f"(joint tracking only)")
    gains = []
    for matrix in (law.gains.kp, law.gains.kv, law.gains.ki):
        diagonal = np.diag(matrix)
        if np.count_nonzero(matrix - np.diag(diagonal)):
            raise NoCImplementation("module kind 'control_law': pid with full gain matrices "
                                    "has no C implementation (diagonal gains only)")
        gains += _floats(diagonal)
    return CKind.LAW_PID, [law.robot.dof, 1.0 if law.params.get("anti_windup", True) else 0.0,
                           *gains, *_constraint(law.constraint)]


def _diagonal(kind: str, matrix: Any) -> list[float]:
    diagonal = np.diag(matrix)
    if np.count_nonzero(matrix - np.diag(diagonal)):
        raise NoCImplementation(f"module kind {kind!r}: full gain matrices have no C "
                                f"implementation (diagonal gains only)")
    return _floats(diagonal)


_AXES = {"JointModelRX": (1.0, 0.0, 0.0), "JointModelRY": (0.0, 1.0, 0.0),
         "JointModelRZ": (0.0, 0.0, 1.0)}
_JOINT_WORDS = 27
MAX_JOINTS = 8
"""Joints of a model in the C runtime (``ORC_MAX_JOINTS``)."""


def _pinocchio(kind: str, model: Any) -> Any:
    from orccad_app.control.models import PinocchioModel

    if type(model) is not PinocchioModel:
        raise NoCImplementation(f"module kind {kind!r}: the {type(model).__name__} has no C "
                                f"implementation (the Pinocchio model, exact or perturbed, has)")
    return model


def _model_damping(kind: str, model: Any) -> list[float]:
    return _floats(_pinocchio(kind, model).damping)


def _model_block(kind: str, model: Any) -> list[float]:
    """The rigid-body model for ``orccad_dynamics.c``, from Pinocchio's model of the robot
    file: gravity, then per joint its parent, axis, placement, body inertia and armature."""
    pin = _pinocchio(kind, model).model
    joints = pin.njoints - 1
    if joints > MAX_JOINTS or pin.nq != joints or pin.nv != joints:
        raise NoCImplementation(f"module kind {kind!r}: the model has {joints} joints of "
                                f"{pin.nq} coordinates; the C runtime's has at most "
                                f"{MAX_JOINTS} revolute joints")
    block = _floats(pin.gravity.linear)
    for index in range(1, pin.njoints):
        joint = pin.joints[index]
        name = joint.shortname()
        axis: tuple[float, ...]
        if name in _AXES:
            axis = _AXES[name]
        elif name == "JointModelRevoluteUnaligned":
            axis = tuple(_floats(joint.extract().axis))
        else:
            raise NoCImplementation(f"module kind {kind!r}: joint {pin.names[index]!r} is a "
                                    f"{name}; the C runtime's model has revolute joints only")
        placement, inertia = pin.jointPlacements[index], pin.inertias[index]
        matrix = np.asarray(inertia.inertia, dtype=float)
        block += [float(pin.parents[index] - 1), *axis, *_floats(placement.rotation),
                  *_floats(placement.translation), float(inertia.mass), *_floats(inertia.lever),
                  matrix[0, 0], matrix[0, 1], matrix[0, 2], matrix[1, 1], matrix[1, 2],
                  matrix[2, 2], float(pin.armature[joint.idx_v])]
    return block


def _dynamic_model(instance: Any) -> tuple[CKind, list[float]]:
    model = instance.model
    return CKind.MODEL_DYN, [model.dof, *_model_damping("dynamic_model", model),
                             *_model_block("dynamic_model", model)]


def _ct_feedback(instance: Any) -> tuple[CKind, list[float]]:
    return CKind.CT_FEEDBACK, [instance.dof, *_diagonal("ct_feedback", instance.kp),
                               *_diagonal("ct_feedback", instance.kv),
                               *_constraint(instance.constraint)]


_MODULES: dict[str, Callable[[Any], tuple[CKind, list[float]]]] = {
    "trajectory": _trajectory,
    "control_law": _control_law,
    "dynamic_model": _dynamic_model,
    "ct_feedback": _ct_feedback,
}


_LIBRARY_LIMITS = {
    "trajectory": "cosine, min_jerk and constant trajectories of joint tracking",
    "control_law": "pid (diagonal gains) and computed_torque of joint tracking",
}
"""What the runtime library's C of a kind covers, where it does not cover every instance."""


def kind_c(kind: Any) -> str | None:
    """Where the C of module or observer ``kind`` is, in words (``orccad plugins -v``):
    the runtime library's (with what it covers), the plugin's file, or ``None``: the kind
    runs only in Python (``orccad sil`` and ``codegen --module-tasks`` refuse it)."""
    name = kind.name
    if name in _MODULES:
        limits = _LIBRARY_LIMITS.get(name)
        return "the runtime library" + (f" ({limits})" if limits else "")
    plugin = getattr(kind, "c_implementation", None)
    if plugin is None:
        return None
    return f"{plugin.source} (prefix {plugin.prefix})"


def c_layout(instance: Any) -> CLayout:
    """The C layout of the module instance ``instance``; raises :class:`NoCImplementation`."""
    name = instance.kind.name
    if name in _MODULES:  # the control library's kinds (orccad_app/control)
        kind, params = _MODULES[name](instance)
    else:
        plugin = getattr(instance.kind, "c_implementation", None)
        if plugin is None:
            raise NoCImplementation(f"module kind {name!r} has no C implementation: it exists "
                                    f"only in Python, so it cannot run in the controller process "
                                    f"(its plugin may provide C: ModuleKind.c_implementation, "
                                    f"docs/deploy.md)")
        return CLayout(CKind.PLUGIN, _ports(instance, "in"), _ports(instance, "out"),
                       _plugin_params(name, plugin, instance), plugin)
    if len(params) > MAX_PARAMS:
        raise NoCImplementation(f"module kind {name!r}: {len(params)} parameters, the C "
                                f"runtime holds {MAX_PARAMS}")
    return CLayout(kind, _ports(instance, "in"), _ports(instance, "out"),
                   tuple(float(v) for v in params))


def _plugin_params(name: str, plugin: Any, instance: Any) -> tuple[float, ...]:
    """The parameter words a plugin kind's C reads (from its declared fields, or the vector it
    gives): finite numbers, within the runtime's."""
    try:
        params = tuple(_floats(plugin.words(instance)))
    except ControlError as error:
        raise NoCImplementation(f"module kind {name!r}: {error.message}") from None
    except (TypeError, ValueError) as error:
        raise NoCImplementation(f"module kind {name!r}: its C implementation's parameters "
                                f"are not numbers ({error})") from None
    if len(params) > MAX_PARAMS:
        raise NoCImplementation(f"module kind {name!r}: {len(params)} parameters, the C "
                                f"runtime holds {MAX_PARAMS}")
    if not all(np.isfinite(params)):
        raise NoCImplementation(f"module kind {name!r}: its C implementation's parameters "
                                f"must be finite")
    return params
