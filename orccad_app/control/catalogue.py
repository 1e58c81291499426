"""The built-in catalogue of kinds: every trajectory, task function, law and module kind that
the built-in ``orccad_control`` plugin registers, in one place.

The classes that do the work live in :mod:`.trajectories`, :mod:`.task_functions`,
:mod:`.laws` and :mod:`.module_kinds`; here each is given its name, summary and declared
parameters (a :mod:`.kinds` entry).
"""

from __future__ import annotations

import math
from typing import Any

from orccad_app.control.errors import ControlError
from orccad_app.control.kinds import LawKind, TaskFunctionKind, TrajectoryKind
from orccad_app.control.laws.pid import PID
from orccad_app.control.laws.scheme import ComputedTorque, GenericScheme
from orccad_app.control.module import ModuleKind
from orccad_app.control.module_kinds import ControlLawModule, TrajectoryModule
from orccad_app.control.multirate import ComputedTorqueFeedbackModule, DynamicModelModule
from orccad_app.control.params import REQUIRED, ParamSpec
from orccad_app.control.robot import RobotType
from orccad_app.control.task_functions import CartesianTracking, JointTracking
from orccad_app.control.trajectories import Constant, Cosine, MinimumJerk

__all__ = ["TRAJECTORY_KINDS", "TASK_FUNCTION_KINDS", "LAW_KINDS", "MODULE_KINDS",
           "COSINE", "MINIMUM_JERK", "CONSTANT", "JOINT_TRACKING", "CARTESIAN_TRACKING",
           "PID_KIND", "GENERIC_KIND", "COMPUTED_TORQUE_KIND"]

# -- trajectories -------------------------------------------------------------------------

COSINE = TrajectoryKind(
    "cosine", "q_d = q0 (1 + cos(omega t)) — RR-1801 eq. 9-10",
    (ParamSpec("q0", "vector", REQUIRED, "half amplitude and offset [rad or m]"),
     ParamSpec("omega", "float", math.pi, "angular frequency [rad/s]", minimum=0.0,
               exclusive=True)),
    lambda p: Cosine(p["q0"], p["omega"]))

MINIMUM_JERK = TrajectoryKind(
    "min_jerk", "minimum-jerk point to point, then hold the goal",
    (ParamSpec("goal", "vector", REQUIRED, "final position [rad or m]"),
     ParamSpec("duration", "float", REQUIRED, "motion time [s]", minimum=0.0, exclusive=True),
     ParamSpec("start", "vector", None, "start position; default: first measurement")),
    lambda p: MinimumJerk(p["goal"], p["duration"], p["start"]))

CONSTANT = TrajectoryKind(
    "constant", "hold a position (default: the first measured one)",
    (ParamSpec("value", "vector", None, "position to hold [rad or m]"),),
    lambda p: Constant(p["value"]))

#: The built-in trajectory kinds, registered by the ``orccad_control`` plugin.
TRAJECTORY_KINDS: tuple[TrajectoryKind, ...] = (COSINE, MINIMUM_JERK, CONSTANT)


# -- task functions -----------------------------------------------------------------------

def _cartesian(params: dict[str, Any], robot: RobotType) -> CartesianTracking:
    frame = params["frame"] or robot.end_effector
    if frame is None:
        raise ControlError(f"cartesian_tracking: robot type {robot.name!r} has no "
                           "'end_effector' site; give frame = \"...\"")
    return CartesianTracking(robot.pinocchio_model(), params["trajectory"], frame,
                             params["damping"])


JOINT_TRACKING = TaskFunctionKind(
    "joint_tracking", "e = q - q_d(t): joint-space trajectory tracking (eq. 6)",
    (ParamSpec("trajectory", "trajectory", REQUIRED, "reference q_d(t) [rad]"),),
    lambda p, robot: JointTracking(robot.dof, p["trajectory"]))

CARTESIAN_TRACKING = TaskFunctionKind(
    "cartesian_tracking", "e = p(q) - p_d(t): end-effector position, DLS inverse",
    (ParamSpec("trajectory", "trajectory", REQUIRED, "reference p_d(t) [m]"),
     ParamSpec("frame", "string", None, "frame name; default: the robot's end effector"),
     ParamSpec("damping", "float", 0.01, "damped-least-squares λ [m]", minimum=0.0)),
    _cartesian)

#: The built-in task function kinds, registered by the ``orccad_control`` plugin.
TASK_FUNCTION_KINDS: tuple[TaskFunctionKind, ...] = (JOINT_TRACKING, CARTESIAN_TRACKING)


# -- control laws -------------------------------------------------------------------------

PID_KIND = LawKind("pid", "PID of eq. 8 (M = I, N = 0), anti-windup", PID.PARAMS, PID)
GENERIC_KIND = LawKind("generic", "generic control scheme of eq. 5 (k, mu, G, D, models)",
                       GenericScheme.PARAMS, GenericScheme)
COMPUTED_TORQUE_KIND = LawKind("computed_torque", "computed torque with the Pinocchio model",
                               ComputedTorque.PARAMS, ComputedTorque)

#: The built-in law kinds, registered by the ``orccad_control`` plugin.
LAW_KINDS: tuple[LawKind, ...] = (PID_KIND, GENERIC_KIND, COMPUTED_TORQUE_KIND)

# -- module kinds -------------------------------------------------------------------------

#: The built-in module kinds (``trajectory``, ``control_law``, and the multi-rate computed
#: torque's ``dynamic_model`` and ``ct_feedback``).
MODULE_KINDS: tuple[ModuleKind, ...] = (TrajectoryModule(), ControlLawModule(),
                                        DynamicModelModule(), ComputedTorqueFeedbackModule())
