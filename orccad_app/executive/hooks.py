"""The observers' callbacks, precomputed per callback name (who listens to what)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from orccad_app.executive.observer import HOOKS, Observer, listeners

__all__ = ["Hooks"]


class Hooks:
    """Per callback name, the list of observers' bound methods that override it."""

    __slots__ = HOOKS

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

    def refresh(self, observers: list[Observer]) -> None:
        """Recompute the listeners in place (holders of this object see the change)."""
        fresh = Hooks(observers)
        for hook in HOOKS:
            listening: list[Any] = getattr(self, hook)
            listening[:] = getattr(fresh, hook)
