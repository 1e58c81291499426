"""The observers' callbacks, precomputed per callback name (who listens to what)."""

from __future__ import annotations

from orccad_app.executive.observer import HOOKS, Observer, listeners

__all__ = ["Hooks"]


class Hooks:
    """Per callback name, the list of observers' bound methods that override it."""

    __slots__ = HOOKS

    def __init__(self, observers: list[Observer]) -> None:
        for hook in HOOKS:
            setattr(self, hook, listeners(observers, hook))

    def refresh(self, observers: list[Observer]) -> None:
        """Recompute the listeners in place (holders of this object see the change)."""
        fresh = Hooks(observers)
        for hook in HOOKS:
            getattr(self, hook)[:] = getattr(fresh, hook)
