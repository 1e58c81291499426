"""The observers' callbacks, precomputed per callback name (who listens to what)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from orccad_app.executive.observer import HOOKS, Observer, listeners

__all__ = ["Hooks"]


class Hooks:
    """Per callback name, the list of observers' bound methods that override it; and per
    output port, the ``on_write`` listeners that want it (:meth:`write_listeners`)."""

    __slots__ = (*HOOKS, "_observers", "_write_listeners")

    on_release: list[Callable[..., None]]
    on_start: list[Callable[..., None]]
    on_preempt: list[Callable[..., None]]
    on_resume: list[Callable[..., None]]
    on_compute_end: list[Callable[..., None]]
    on_finish: list[Callable[..., None]]
    on_overrun: list[Callable[..., None]]
    on_block: list[Callable[..., None]]
    on_unblock: list[Callable[..., None]]
    on_read: list[Callable[..., None]]
    on_write: list[Callable[..., None]]
    on_signal: list[Callable[..., None]]
    on_message: list[Callable[..., None]]
    on_activate: list[Callable[..., None]]
    on_kill: list[Callable[..., None]]
    on_param: list[Callable[..., None]]
    on_deadlock: list[Callable[..., None]]

    def __init__(self, observers: list[Observer]) -> None:
        for hook in HOOKS:
            setattr(self, hook, listeners(observers, hook))
        self._observers = list(observers)
        self._write_listeners: dict[tuple[str, str], list[Callable[..., None]]] = {}

    def refresh(self, observers: list[Observer]) -> None:
        """Recompute the listeners in place (holders of this object see the change)."""
        fresh = Hooks(observers)
        for hook in HOOKS:
            listening: list[Any] = getattr(self, hook)
            listening[:] = getattr(fresh, hook)
        self._observers = list(observers)
        for (module, port), listening in self._write_listeners.items():
            listening[:] = self._wanting(module, port)

    def write_listeners(self, module: str, port: str) -> list[Callable[..., None]]:
        """The ``on_write`` listeners of ``module.port``: those whose observer
        :meth:`~orccad_app.executive.observer.Observer.wants_write` it. The same list object
        for the life of the hooks, updated in place by :meth:`refresh`."""
        key = (module, port)
        found = self._write_listeners.get(key)
        if found is None:
            found = self._write_listeners[key] = self._wanting(module, port)
        return found

    def _wanting(self, module: str, port: str) -> list[Callable[..., None]]:
        wanting = []
        for hook in self.on_write:
            wants = getattr(getattr(hook, "__self__", None), "wants_write", None)
            if wants is None or wants(module, port):
                wanting.append(hook)
        return wanting
