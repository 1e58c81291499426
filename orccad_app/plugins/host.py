"""The plugin host: a typed facade over ``pluggy.PluginManager``.

Start-up (:meth:`PluginHost.load`):

1. load the plugins of the entry-point group ``orccad`` — the built-in ones
   (``orccad_control``, ``orccad_arm3dof``, ``orccad_observers``) come through the same
   path as third-party ones — except those named in ``ORCCAD_DISABLE_PLUGINS``
   (comma-separated);
2. ``check_pending()``: a hook implementation that matches no specification (a typo) is
   an error of its plugin;
3. call the registration hooks of each plugin, then ``orccad_plugins_loaded``, through
   :attr:`PluginHost.hooks` (:class:`~orccad_app.plugins.hooks.OrccadHooks`, one method
   per hook).

A plugin that fails to import, fails validation, raises in a hook or registers an invalid
or duplicate item is recorded in :attr:`PluginHost.failures` with its name, its
contributions are withdrawn and it is unregistered; the other plugins keep working.
"""

from __future__ import annotations

import inspect
import os
from collections.abc import Iterable
from dataclasses import dataclass
from importlib import metadata
from typing import Any

import pluggy

from orccad_app.control.kinds import LawKind, TaskFunctionKind, TrajectoryKind
from orccad_app.control.module import ModuleKind
from orccad_app.control.robot import RobotType
from orccad_app.diagnostics import OrccadError
from orccad_app.plugins import hookspecs
from orccad_app.plugins.hooks import OrccadHooks, describe_error
from orccad_app.plugins.registry import Registries, Registry

__all__ = [
    "ENTRY_POINT_GROUP",
    "DISABLE_ENV",
    "PluginInfo",
    "PluginFailure",
    "PluginHost",
    "default_host",
    "reset_default_host",
]

#: Entry-point group of ORCCAD plugins.
ENTRY_POINT_GROUP = hookspecs.PROJECT
#: Environment variable listing plugin names not to load, comma-separated.
DISABLE_ENV = "ORCCAD_DISABLE_PLUGINS"

_IMPL_DEFAULTS = dict(wrapper=False, hookwrapper=False, optionalhook=False,
                      tryfirst=False, trylast=False, specname=None)


@dataclass(frozen=True)
class PluginInfo:
    """A loaded plugin: its ``name``, Python ``module`` and distribution, if any."""

    name: str
    module: str
    distribution: str | None = None
    version: str | None = None


@dataclass(frozen=True)
class PluginFailure:
    """Plugin ``plugin`` failed at ``stage`` (``import``, ``validation`` or a hook)."""

    plugin: str
    stage: str
    message: str

    def format(self) -> str:
        """One line for users: ``plugin 'x' disabled: <stage>: <message>``."""
        return f"plugin {self.plugin!r} disabled: {self.stage}: {self.message}"


class _Manager(pluggy.PluginManager):
    """Also accepts unmarked functions named ``orccad_*`` as hook implementations."""

    def parse_hookimpl_opts(self, plugin: Any, name: str) -> Any:
        opts = super().parse_hookimpl_opts(plugin, name)
        if opts is None and name.startswith(f"{hookspecs.PROJECT}_"):
            if inspect.isroutine(getattr(plugin, name, None)):
                return dict(_IMPL_DEFAULTS)
        return opts


def _blocked_from_env() -> set[str]:
    return {name.strip() for name in os.environ.get(DISABLE_ENV, "").split(",") if name.strip()}


class PluginHost:
    """Plugins, their registries and their failures. Build one with :meth:`load`."""

    def __init__(self, blocked: Iterable[str] = ()):
        self.manager = _Manager(hookspecs.PROJECT)
        self.manager.add_hookspecs(hookspecs)
        self.registries = Registries.empty()
        self.plugins: dict[str, PluginInfo] = {}
        self.failures: list[PluginFailure] = []
        self.blocked: set[str] = set(blocked)
        for name in self.blocked:
            self.manager.set_blocked(name)
        self._started = False
        #: the typed facade that calls each hook plugin by plugin
        self.hooks = OrccadHooks(self.manager, lambda name: name in self.plugins, self.disable)

    # -- registries --------------------------------------------------------------------

    @property
    def robot_types(self) -> Registry[RobotType]:
        """Robot types (:class:`~orccad_app.control.RobotType`)."""
        return self.registries.robot_types

    @property
    def control_laws(self) -> Registry[LawKind]:
        """Control laws (:class:`~orccad_app.control.LawKind`)."""
        return self.registries.control_laws

    @property
    def task_functions(self) -> Registry[TaskFunctionKind]:
        """Task functions (:class:`~orccad_app.control.TaskFunctionKind`)."""
        return self.registries.task_functions

    @property
    def trajectories(self) -> Registry[TrajectoryKind]:
        """Trajectories (:class:`~orccad_app.control.TrajectoryKind`)."""
        return self.registries.trajectories

    @property
    def observers(self) -> Registry[ModuleKind]:
        """Observer module kinds (with an ``event`` output)."""
        return self.registries.observers

    @property
    def module_kinds(self) -> Registry[ModuleKind]:
        """Other module kinds (``trajectory``, ``control_law``…)."""
        return self.registries.module_kinds

    def module_kind(self, name: str) -> ModuleKind:
        """A module kind or observer by name (what ``module x : NAME`` may use)."""
        if name in self.module_kinds:
            return self.module_kinds.get(name)
        if name in self.observers:
            return self.observers.get(name)
        raise self.module_kinds.unknown(name, self.observers.names())

    # -- loading -----------------------------------------------------------------------

    @classmethod
    def load(cls, plugins: Iterable[tuple[str, Any]] = (), entry_points: bool = True,
             blocked: Iterable[str] | None = None) -> PluginHost:
        """A started host: entry-point plugins (unless ``entry_points=False``), then the
        extra ``(name, plugin)`` pairs. ``blocked`` defaults to ``ORCCAD_DISABLE_PLUGINS``."""
        host = cls(_blocked_from_env() if blocked is None else blocked)
        if entry_points:
            host.load_entry_points()
        for name, plugin in plugins:
            host.add_plugin(plugin, name)
        return host.start()

    def load_entry_points(self, group: str = ENTRY_POINT_GROUP) -> None:
        """Import and register every plugin of ``group`` not blocked (first name wins)."""
        for entry_point in metadata.entry_points(group=group):
            name = entry_point.name
            if name in self.blocked or name in self.plugins:
                continue
            dist = getattr(entry_point, "dist", None)
            try:
                plugin = entry_point.load()
            except Exception as error:  # noqa: BLE001 - any import error is the plugin's
                self.failures.append(PluginFailure(name, "import", describe_error(error)))
                continue
            self.add_plugin(plugin, name, dist.name if dist else None,
                            dist.version if dist else None)

    def add_plugin(self, plugin: Any, name: str, distribution: str | None = None,
                   version: str | None = None) -> bool:
        """Register ``plugin`` under ``name`` before :meth:`start`; False if refused."""
        if self._started:
            raise OrccadError(f"plugin {name!r}: the plugin host has already started")
        if name in self.blocked:
            return False
        if name in self.plugins:
            self.failures.append(PluginFailure(name, "validation", "a plugin of that name is "
                                               f"already loaded from {self.plugins[name].module}"))
            return False
        try:
            self.manager.register(plugin, name=name)
        except (pluggy.PluginValidationError, ValueError) as error:
            self.failures.append(PluginFailure(name, "validation", describe_error(error)))
            return False
        module = getattr(plugin, "__name__", type(plugin).__qualname__)
        self.plugins[name] = PluginInfo(name, module, distribution, version)
        return True

    def start(self) -> PluginHost:
        """``check_pending``, then the registration hooks, then ``orccad_plugins_loaded``."""
        if self._started:
            return self
        self._started = True
        self._check_pending()
        hooks, registries = self.hooks, self.registries
        hooks.register_robot_types(registries.robot_types)
        hooks.register_control_laws(registries.control_laws)
        hooks.register_task_functions(registries.task_functions)
        hooks.register_trajectories(registries.trajectories)
        hooks.register_observers(registries.observers)
        hooks.register_module_kinds(registries.module_kinds)
        hooks.plugins_loaded(self)
        return self

    def _check_pending(self) -> None:
        while True:
            try:
                self.manager.check_pending()
                return
            except pluggy.PluginValidationError as error:
                name = self.manager.get_name(error.plugin) or repr(error.plugin)
                self.disable(name, "validation", str(error))

    def disable(self, plugin: str, stage: str, message: str) -> None:
        """Record a failure of ``plugin``, withdraw its contributions and unregister it."""
        self.failures.append(PluginFailure(plugin, stage, message))
        self.registries.remove_plugin(plugin)
        self.plugins.pop(plugin, None)
        registered = self.manager.get_plugin(plugin)
        if registered is not None:
            self.manager.unregister(registered)

    def provider(self, category: str, name: str) -> str:
        """The plugin that provides ``name`` in registry ``category`` (e.g. ``observers``)."""
        return getattr(self.registries, category).plugin_of(name)


_DEFAULT: PluginHost | None = None


def default_host() -> PluginHost:
    """The process-wide host, loaded from entry points on first use."""
    global _DEFAULT
    if _DEFAULT is None:
        _DEFAULT = PluginHost.load()
    return _DEFAULT


def reset_default_host() -> None:
    """Forget the process-wide host (tests, or after installing a plugin)."""
    global _DEFAULT
    _DEFAULT = None
