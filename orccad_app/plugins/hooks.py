"""Typed facade over the hooks: one method per hook of :mod:`.hookspecs`.

Each method calls every active plugin's implementation *alone*, in registration order,
so that a plugin that raises is reported (``on_failure(plugin, stage, message)``) without
stopping the others, and so that every registered item is attributed to its plugin.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import pluggy

from orccad_app.control.kinds import LawKind, TaskFunctionKind, TrajectoryKind
from orccad_app.control.module import ModuleKind
from orccad_app.control.robot import RobotType
from orccad_app.diagnostics import OrccadError
from orccad_app.plugins.registry import Registry

if TYPE_CHECKING:
    from orccad_app.plugins.host import PluginHost

__all__ = ["OrccadHooks", "describe_error"]

#: ``on_failure(plugin, stage, message)``
FailureHandler = Callable[[str, str, str], None]


def describe_error(error: BaseException) -> str:
    """A one-line description of an exception raised by a plugin."""
    if isinstance(error, OrccadError):
        return error.message
    return f"{type(error).__name__}: {error}"


class _Collector:
    """The ``register`` callable given to a registration hook: collects the items."""

    def __init__(self) -> None:
        self.items: list[Any] = []

    def __call__(self, item: Any) -> None:
        self.items.append(item)


class OrccadHooks:
    """Calls the hooks of ``manager``'s plugins for which ``is_active(name)`` holds."""

    def __init__(self, manager: pluggy.PluginManager, is_active: Callable[[str], bool],
                 on_failure: FailureHandler):
        self._manager = manager
        self._is_active = is_active
        self._on_failure = on_failure

    # -- phase 1: registration ---------------------------------------------------------

    def register_robot_types(self, registry: Registry[RobotType]) -> None:
        """``orccad_register_robot_types`` of each plugin, into ``registry``."""
        self._register("orccad_register_robot_types", registry)

    def register_control_laws(self, registry: Registry[LawKind]) -> None:
        """``orccad_register_control_laws`` of each plugin, into ``registry``."""
        self._register("orccad_register_control_laws", registry)

    def register_task_functions(self, registry: Registry[TaskFunctionKind]) -> None:
        """``orccad_register_task_functions`` of each plugin, into ``registry``."""
        self._register("orccad_register_task_functions", registry)

    def register_trajectories(self, registry: Registry[TrajectoryKind]) -> None:
        """``orccad_register_trajectories`` of each plugin, into ``registry``."""
        self._register("orccad_register_trajectories", registry)

    def register_observers(self, registry: Registry[ModuleKind]) -> None:
        """``orccad_register_observers`` of each plugin, into ``registry``."""
        self._register("orccad_register_observers", registry)

    def register_module_kinds(self, registry: Registry[ModuleKind]) -> None:
        """``orccad_register_module_kinds`` of each plugin, into ``registry``."""
        self._register("orccad_register_module_kinds", registry)

    # -- phase 2: start-up complete ----------------------------------------------------

    def plugins_loaded(self, host: PluginHost) -> None:
        """``orccad_plugins_loaded(host)`` of each plugin."""
        self._call_each("orccad_plugins_loaded", lambda: {"host": host})

    # -- plumbing ----------------------------------------------------------------------

    def _register(self, hook_name: str, registry: Registry[Any]) -> None:
        """Items are added only if the plugin's hook returned normally; the first invalid
        or duplicate item fails the plugin."""
        for plugin, kwargs in self._call_each(hook_name, lambda: {"register": _Collector()}):
            for item in kwargs["register"].items:
                try:
                    registry.add(item, plugin)
                except OrccadError as error:
                    self._on_failure(plugin, hook_name, error.message)
                    break

    def _call_each(self, hook_name: str, arguments: Callable[[], dict[str, Any]]
                   ) -> list[tuple[str, dict[str, Any]]]:
        """``(plugin, arguments)`` of the calls that returned normally."""
        done = []
        hook = getattr(self._manager.hook, hook_name)
        for impl in hook.get_hookimpls():  # registration order (pluggy calls them reversed)
            name = impl.plugin_name
            if not self._is_active(name):
                continue
            kwargs = arguments()
            try:
                impl.function(**{arg: kwargs[arg] for arg in impl.argnames})
            except Exception as error:  # noqa: BLE001 - a plugin must not crash the host
                self._on_failure(name, hook_name, describe_error(error))
                continue
            done.append((name, kwargs))
        return done
