"""Hook specifications of ORCCAD plugins (pluggy project ``"orccad"``).

A plugin is a module (or object) registered under the entry-point group ``orccad``. It
implements some of these hooks, marked with :data:`orccad_app.plugin_api.hookimpl` (functions
named ``orccad_*`` are also recognized without the marker; a misspelt hook name is an
error reported at start-up). Every hook is called once per plugin. A plugin that raises,
or registers something invalid, is reported with its name and disabled; the others keep
working.

The hooks below are grouped by the phase in which the host calls them. ``docs/plugins.md``
documents each one for plugin authors.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import pluggy

from orccad_app.plugin_host.registry import CATEGORIES

__all__ = ["PROJECT", "hookspec", "hookimpl", "Register", "REGISTRATION_HOOKS", "STARTUP_HOOKS"]

#: The pluggy project name, also the entry-point group.
PROJECT = "orccad"

hookspec = pluggy.HookspecMarker(PROJECT)

#: Marks a function of a plugin as the implementation of an ORCCAD hook (plugins import it
#: from :mod:`orccad_app.plugin_api`).
hookimpl = pluggy.HookimplMarker(PROJECT)

#: ``register(item)`` adds one item to a registry under ``item.name``.
Register = Callable[[Any], None]


# --------------------------------------------------------------------------------------
# Phase 1 — registration. At start-up, in this order, for each plugin in turn.
# Each receives ``register``: call it once per item; the host records the plugin's name
# as the item's provider. Names must be unique across plugins.
# --------------------------------------------------------------------------------------


@hookspec
def orccad_register_robot_types(register: Register) -> None:
    """Register robot types: :class:`orccad_app.plugin_api.RobotType` objects.

    A robot type is a physical resource described by one MJCF file (joints, limits,
    ``jointpos``/``jointvel`` sensors, ``motor`` actuators); build it with
    ``RobotType.from_mjcf(name, path, summary)``. Plans declare ``robot arm : NAME;``.
    """


@hookspec
def orccad_register_control_laws(register: Register) -> None:
    """Register control laws: :class:`orccad_app.plugin_api.LawKind` objects.

    A law kind names a :class:`~orccad_app.plugin_api.ControlLaw` subclass and its
    parameters; the Robot-Task's ``law NAME(args);`` selects it.
    """


@hookspec
def orccad_register_task_functions(register: Register) -> None:
    """Register task functions: :class:`orccad_app.plugin_api.TaskFunctionKind` objects.

    Used by ``task_function NAME(args);``; the factory receives the validated parameters
    and the robot type, and must check ``dim e`` against the robot.
    """


@hookspec
def orccad_register_trajectories(register: Register) -> None:
    """Register trajectories: :class:`orccad_app.plugin_api.TrajectoryKind` objects.

    Used as the ``trajectory = NAME(args)`` argument of task functions.
    """


@hookspec
def orccad_register_observers(register: Register) -> None:
    """Register observers: :class:`orccad_app.plugin_api.ModuleKind` objects with at least
    one ``event`` output port.

    Observers watch signals and emit events that a Robot-Task maps to pre-conditions,
    exceptions and post-conditions (``exception E from NAME(args) : abort;``).
    """


@hookspec
def orccad_register_module_kinds(register: Register) -> None:
    """Register other module kinds: :class:`orccad_app.plugin_api.ModuleKind` objects.

    Module kinds are the periodic Module-Tasks of the time-constrained specification
    (``module NAME : KIND(args) period … wcet …;``).
    """


# --------------------------------------------------------------------------------------
# Phase 2 — start-up complete. Once, after every plugin's registration hooks.
# --------------------------------------------------------------------------------------


@hookspec
def orccad_plugins_loaded(host: Any) -> None:
    """Called once all registrations are done, with the
    :class:`~orccad_app.plugin_api.PluginHost`.

    Use it for checks across plugins (e.g. that a robot type you extend is present) —
    raise :class:`~orccad_app.plugin_api.OrccadError` to report a problem; the plugin is
    then disabled. Do not register items here.
    """


#: Registration hooks, in calling order, with the host registry each fills (from the table
#: :data:`~orccad_app.plugin_host.registry.CATEGORIES`).
REGISTRATION_HOOKS: tuple[tuple[str, str], ...] = tuple((c.hook, c.attribute) for c in CATEGORIES)

#: Hooks of phase 2.
STARTUP_HOOKS: tuple[str, ...] = ("orccad_plugins_loaded",)
