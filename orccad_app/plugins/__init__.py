"""Plugins: hook specifications, registries and the plugin host (pluggy).

Plugin authors import :data:`hookimpl` to mark hook implementations; the rest of ORCCAD
uses :func:`default_host` to reach the registries::

    from orccad_app.plugins import default_host
    host = default_host()
    arm = host.robot_types.get("arm3dof")
    pid = host.control_laws.get("pid")
    host.module_kind("joint_limits")      # module kinds and observers
"""

import pluggy

from orccad_app.plugins.hooks import OrccadHooks
from orccad_app.plugins.hookspecs import PROJECT, REGISTRATION_HOOKS, STARTUP_HOOKS, hookspec
from orccad_app.plugins.host import (
    DISABLE_ENV,
    ENTRY_POINT_GROUP,
    PluginFailure,
    PluginHost,
    PluginInfo,
    default_host,
    reset_default_host,
)
from orccad_app.plugins.registry import Entry, Registries, Registry

__all__ = [
    "hookimpl",
    "hookspec",
    "PROJECT",
    "REGISTRATION_HOOKS",
    "STARTUP_HOOKS",
    "ENTRY_POINT_GROUP",
    "DISABLE_ENV",
    "PluginHost",
    "OrccadHooks",
    "PluginInfo",
    "PluginFailure",
    "Registry",
    "Registries",
    "Entry",
    "default_host",
    "reset_default_host",
]

#: Marks a function of a plugin as the implementation of an ORCCAD hook.
hookimpl = pluggy.HookimplMarker(PROJECT)
