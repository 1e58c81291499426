"""Typed facade over the hooks: one method per hook of :mod:`.hookspecs`.

Each method calls every active plugin's implementation *alone*, in registration order,
so that a plugin that raises is reported (``on_failure(plugin, stage, message)``) without
stopping the others, and so that every registered item is attributed to its plugin.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import pluggy

from orccad_app.diagnostics import OrccadError
from orccad_app.plugin_host.registry import Category, NameClash, Registry

__all__ = ["OrccadHooks", "describe_error"]

#: ``on_failure(plugin, stage, message)``: the plugin is disabled.
FailureHandler = Callable[[str, str, str], None]
#: ``on_clash(plugin, stage, message)``: one contribution of the plugin is refused.
ClashHandler = Callable[[str, str, str], None]


def describe_error(error: BaseException) -> str:
    """A one-line description of an exception raised by a plugin."""
    if isinstance(error, OrccadError):
        return error.message
    if isinstance(error, SystemExit):
        return f"called sys.exit({error.code!r})"
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
                 on_failure: FailureHandler, on_clash: ClashHandler | None = None):
        self._manager = manager
        self._is_active = is_active
        self._on_failure = on_failure
        self._on_clash = on_clash or on_failure

    # -- phase 1: registration ---------------------------------------------------------

    def register(self, category: Category, registry: Registry[Any]) -> None:
        """The registration hook of ``category`` for each plugin, into ``registry``."""
        self._register(category.hook, registry)

    # -- phase 2: start-up complete ----------------------------------------------------

    def plugins_loaded(self, host: object) -> None:
        """``orccad_plugins_loaded(host)`` of each plugin."""
        self._call_each("orccad_plugins_loaded", lambda: {"host": host})

    # -- plumbing ----------------------------------------------------------------------

    def _register(self, hook_name: str, registry: Registry[Any]) -> None:
        """Items are added only if the plugin's hook returned normally; the first invalid
        item fails the plugin; an item whose name another plugin already provides is refused
        alone (the plugin's other contributions stay)."""
        for plugin, kwargs in self._call_each(hook_name, lambda: {"register": _Collector()}):
            for item in kwargs["register"].items:
                try:
                    registry.add(item, plugin)
                except NameClash as clash:
                    self._on_clash(plugin, hook_name, clash.message)
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
            except (Exception, SystemExit) as error:  # noqa: BLE001 - a plugin must not
                # crash the host, not even by calling sys.exit() in a hook
                self._on_failure(name, hook_name, describe_error(error))
                continue
            done.append((name, kwargs))
        return done
