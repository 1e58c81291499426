"""Built-in plugin ``orccad_control``: the control library of ``orccad_app.control``.

Registers the trajectories (``cosine``, ``min_jerk``, ``constant``), the task functions
(``joint_tracking``, ``cartesian_tracking``), the control laws (``pid``, ``generic``,
``computed_torque``) and the generic module kinds (``trajectory``, ``control_law``, and
``dynamic_model`` and ``ct_feedback``: computed torque split at two rates). It is
loaded through the ``orccad`` entry-point group like any third-party plugin.
"""

from orccad_app.plugin_api import (
    LAW_KINDS,
    MODULE_KINDS,
    TASK_FUNCTION_KINDS,
    TRAJECTORY_KINDS,
    hookimpl,
)

__all__ = [
    "orccad_register_control_laws",
    "orccad_register_task_functions",
    "orccad_register_trajectories",
    "orccad_register_module_kinds",
]


@hookimpl
def orccad_register_control_laws(register):
    """PID (eq. 8), the generic scheme (eq. 5) and computed torque."""
    for kind in LAW_KINDS:
        register(kind)


@hookimpl
def orccad_register_task_functions(register):
    """Joint tracking (eq. 6) and Cartesian end-effector position tracking."""
    for kind in TASK_FUNCTION_KINDS:
        register(kind)


@hookimpl
def orccad_register_trajectories(register):
    """Cosine (eq. 9-10), minimum jerk and constant."""
    for kind in TRAJECTORY_KINDS:
        register(kind)


@hookimpl
def orccad_register_module_kinds(register):
    """The ``trajectory``, ``control_law``, ``dynamic_model`` and ``ct_feedback`` Module-Tasks."""
    for kind in MODULE_KINDS:
        register(kind)
