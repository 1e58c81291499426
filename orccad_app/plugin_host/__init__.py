"""Plugins: hook specifications, registries and the plugin host (pluggy).

Plugin authors import from :mod:`orccad_app.plugin_api` only. The rest of ORCCAD loads a
host and passes it explicitly (there is no process-wide one)::

    from orccad_app.plugin_host import PluginHost
    host = PluginHost.load()
    arm = host.robot_types.get("arm3dof")
    pid = host.control_laws.get("pid")
    host.module_kind("joint_limits")      # module kinds and observers
"""

from orccad_app.plugin_host.hooks import OrccadHooks
from orccad_app.plugin_host.hookspecs import (
    PROJECT,
    REGISTRATION_HOOKS,
    STARTUP_HOOKS,
    hookimpl,
    hookspec,
)
from orccad_app.plugin_host.host import (
    DISABLE_ENV,
    ENTRY_POINT_GROUP,
    PluginFailure,
    PluginHost,
    PluginInfo,
)
from orccad_app.plugin_host.registry import (
    CATEGORIES,
    Category,
    Entry,
    NameClash,
    Registries,
    Registry,
)

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
    "Category",
    "CATEGORIES",
    "NameClash",
]
