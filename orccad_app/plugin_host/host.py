"""The plugin host: a typed facade over ``pluggy.PluginManager``.

Start-up (:meth:`PluginHost.load`):

1. load the plugins of the entry-point group ``orccad`` — the built-in ones
   (``orccad_control``, ``orccad_arm3dof``, ``orccad_observers``) come through the same
   path as third-party ones — except those named in ``ORCCAD_DISABLE_PLUGINS``
   (comma-separated);
2. ``check_pending()``: a hook implementation that matches no specification (a typo) is
   an error of its plugin;
3. call the registration hook of each category of
   :data:`~orccad_app.plugin_host.registry.CATEGORIES` (the one table registration is driven
   by) for each plugin, then ``orccad_plugins_loaded``, through :attr:`PluginHost.hooks`
   (:class:`~orccad_app.plugin_host.hooks.OrccadHooks`).

A plugin that fails to import, fails validation, raises in a hook or registers an invalid
item is recorded in :attr:`PluginHost.failures` with its name, its contributions are
withdrawn and it is unregistered; the other plugins keep working. An item whose name another
plugin already provides is refused alone (the failure names both plugins; the plugin stays).

There is no process-wide host: whoever needs the registries loads one
(:meth:`PluginHost.load`) and passes it on (``orccad_app.pipeline.load(path, host)``).
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
from orccad_app.plugin_host import hookspecs
from orccad_app.plugin_host.hooks import OrccadHooks, describe_error
from orccad_app.plugin_host.registry import CATEGORIES, Registries, Registry

__all__ = [
    "ENTRY_POINT_GROUP",
    "DISABLE_ENV",
    "PluginInfo",
    "PluginFailure",
    "PluginHost",
]

#: Entry-point group of ORCCAD plugins.
ENTRY_POINT_GROUP = hookspecs.PROJECT
#: Environment variable listing plugin names not to load, comma-separated.
DISABLE_ENV = "ORCCAD_DISABLE_PLUGINS"

_OWN_DISTRIBUTION = "orccad"

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
    """Plugin ``plugin`` failed at ``stage`` (``import``, ``validation`` or a hook).

    :param disabled: the plugin was disabled; ``False`` when only one contribution was
        refused (a name another plugin already provides).
    """

    plugin: str
    stage: str
    message: str
    disabled: bool = True

    def format(self) -> str:
        """One line for users: ``plugin 'x' disabled: <stage>: <message>`` (or ``plugin 'x':
        <stage>: <message>`` when only a contribution was refused)."""
        state = " disabled" if self.disabled else ""
        return f"plugin {self.plugin!r}{state}: {self.stage}: {self.message}"


class _Manager(pluggy.PluginManager):
    """Also accepts unmarked functions named ``orccad_*`` as hook implementations."""

    def parse_hookimpl_opts(self, plugin: Any, name: str) -> Any:
        opts = super().parse_hookimpl_opts(plugin, name)
        if opts is None and name.startswith(f"{hookspecs.PROJECT}_"):
            if inspect.isroutine(getattr(plugin, name, None)):
                return dict(_IMPL_DEFAULTS)
        return opts


def _third_party(entry_point: metadata.EntryPoint) -> bool:
    """Sort key: built-in plugins (of the ``orccad`` distribution) before the others."""
    dist = getattr(entry_point, "dist", None)
    return dist is None or dist.name != _OWN_DISTRIBUTION


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
        self.hooks = OrccadHooks(self.manager, lambda name: name in self.plugins, self.disable,
                                 self.refuse)

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
        """Import and register every plugin of ``group`` not blocked (first name wins): the
        built-in plugins (the ``orccad`` distribution's) first, so that on a name clash the
        built-in contribution is kept and the third-party one refused."""
        for entry_point in sorted(metadata.entry_points(group=group), key=_third_party):
            name = entry_point.name
            if name in self.blocked or name in self.plugins:
                continue
            dist = getattr(entry_point, "dist", None)
            try:
                plugin = entry_point.load()
            except (Exception, SystemExit) as error:  # noqa: BLE001 - the plugin's, even
                # sys.exit() at import: the plugin is disabled, the command goes on
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
        for category in CATEGORIES:
            self.hooks.register(category, self.registries[category.attribute])
        self.hooks.plugins_loaded(self)
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

    def refuse(self, plugin: str, stage: str, message: str) -> None:
        """Record that one contribution of ``plugin`` was refused (the plugin stays)."""
        self.failures.append(PluginFailure(plugin, stage, message, disabled=False))

    def warn_failures(self, stream: Any = None) -> None:
        """Print each failure once as ``orccad: warning: …`` (to stderr by default)."""
        import sys
        for failure in self.failures:
            print(f"orccad: warning: {failure.format()}", file=stream or sys.stderr)

    def provider(self, category: str, name: str) -> str:
        """The plugin that provides ``name`` in registry ``category`` (e.g. ``observers``)."""
        return getattr(self.registries, category).plugin_of(name)
