"""Registries: one per category of plugin contribution, each entry with its provider.

Lookups of unknown names raise :class:`~orccad_app.diagnostics.OrccadError` naming the
name, the close matches (difflib) and what is known.
"""

from __future__ import annotations

import difflib
from collections.abc import Callable, Iterator
from dataclasses import dataclass, fields
from typing import Any, Generic, TypeVar

from orccad_app.control.kinds import LawKind, TaskFunctionKind, TrajectoryKind
from orccad_app.control.module import ModuleKind
from orccad_app.control.robot import RobotType
from orccad_app.diagnostics import OrccadError

__all__ = ["Entry", "Registry", "Registries"]

T = TypeVar("T")


@dataclass(frozen=True)
class Entry(Generic[T]):
    """A registered ``item`` under ``name``, provided by the plugin named ``plugin``."""

    name: str
    item: T
    plugin: str


class Registry(Generic[T]):
    """Named items of one ``category`` (e.g. ``"robot type"``), in registration order.

    ``check(item)`` returns an error message for an invalid item, or ``None``.
    """

    def __init__(self, category: str, check: Callable[[Any], str | None] | None = None):
        self.category = category
        self._check = check
        self._entries: dict[str, Entry[T]] = {}

    def add(self, item: T, plugin: str) -> None:
        """Register ``item`` under ``item.name`` for ``plugin``; raises on a bad item or
        a name another plugin already provides."""
        name = getattr(item, "name", None)
        if not isinstance(name, str) or not name:
            raise OrccadError(f"{self.category} {item!r} has no name")
        problem = self._check(item) if self._check else None
        if problem:
            raise OrccadError(f"{self.category} {name!r}: {problem}")
        if name in self._entries:
            other = self._entries[name].plugin
            raise OrccadError(f"{self.category} {name!r} is already provided by plugin {other!r}")
        self._entries[name] = Entry(name, item, plugin)

    def remove_plugin(self, plugin: str) -> None:
        """Forget every item ``plugin`` provided."""
        self._entries = {k: e for k, e in self._entries.items() if e.plugin != plugin}

    def entry(self, name: str) -> Entry[T]:
        """The entry ``name``; unknown names raise listing close matches."""
        try:
            return self._entries[name]
        except KeyError:
            raise self.unknown(name) from None

    def get(self, name: str) -> T:
        """The item ``name``; unknown names raise listing close matches."""
        return self.entry(name).item

    def plugin_of(self, name: str) -> str:
        """Name of the plugin that provides ``name``."""
        return self.entry(name).plugin

    def unknown(self, name: str, extra: list[str] | None = None) -> OrccadError:
        """The error for an unknown ``name`` (``extra``: more candidate names)."""
        known = self.names() + (extra or [])
        matches = difflib.get_close_matches(name, known, n=3, cutoff=0.6)
        hint = (" (did you mean " + " or ".join(map(repr, matches)) + "?)") if matches else ""
        listing = ", ".join(known) if known else "none installed"
        return OrccadError(f"unknown {self.category} {name!r}{hint}; known: {listing}")

    def names(self) -> list[str]:
        """Registered names in registration order."""
        return list(self._entries)

    def entries(self) -> list[Entry[T]]:
        """Entries in registration order."""
        return list(self._entries.values())

    def __contains__(self, name: object) -> bool:
        return name in self._entries

    def __iter__(self) -> Iterator[T]:
        return (entry.item for entry in self._entries.values())

    def __len__(self) -> int:
        return len(self._entries)

    def __repr__(self) -> str:
        return f"<{self.category} registry: {', '.join(self._entries)}>"


def _instance_of(kind: type, label: str) -> Callable[[Any], str | None]:
    def check(item: Any) -> str | None:
        return None if isinstance(item, kind) else f"must be a {label}, got {type(item).__name__}"
    return check


def _observer(item: Any) -> str | None:
    if not isinstance(item, ModuleKind):
        return f"must be a ModuleKind, got {type(item).__name__}"
    return None if item.is_observer else "an observer needs at least one 'event' output port"


@dataclass
class Registries:
    """The six registries the plugins fill."""

    robot_types: Registry[RobotType]
    control_laws: Registry[LawKind]
    task_functions: Registry[TaskFunctionKind]
    trajectories: Registry[TrajectoryKind]
    observers: Registry[ModuleKind]
    module_kinds: Registry[ModuleKind]

    @classmethod
    def empty(cls) -> Registries:
        """Fresh, empty registries with their item checks."""
        return cls(
            robot_types=Registry("robot type", _instance_of(RobotType, "RobotType")),
            control_laws=Registry("control law", _instance_of(LawKind, "LawKind")),
            task_functions=Registry("task function",
                                    _instance_of(TaskFunctionKind, "TaskFunctionKind")),
            trajectories=Registry("trajectory", _instance_of(TrajectoryKind, "TrajectoryKind")),
            observers=Registry("observer", _observer),
            module_kinds=Registry("module kind", _instance_of(ModuleKind, "ModuleKind")),
        )

    def all(self) -> list[tuple[str, Registry[Any]]]:
        """``(attribute name, registry)`` pairs in a stable order."""
        return [(f.name, getattr(self, f.name)) for f in fields(self)]

    def remove_plugin(self, plugin: str) -> None:
        """Forget everything ``plugin`` provided, in every registry."""
        for _, registry in self.all():
            registry.remove_plugin(plugin)
