"""Registries: one per category of plugin contribution, each entry with its provider.

Lookups of unknown names raise :class:`~orccad_app.diagnostics.OrccadError` naming the
name, the close matches (difflib) and what is known.
"""

from __future__ import annotations

import difflib
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from typing import Any, Generic, TypeVar

from orccad_app.control.kinds import LawKind, TaskFunctionKind, TrajectoryKind
from orccad_app.control.module import ModuleKind
from orccad_app.control.robot import RobotType
from orccad_app.diagnostics import OrccadError

__all__ = ["Entry", "Registry", "Registries", "NameClash", "Category", "CATEGORIES"]

T = TypeVar("T")


class NameClash(OrccadError):
    """A plugin registers a name another plugin already provides (only that item is
    refused; the first provider keeps it)."""


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
            raise NameClash(f"{self.category} {name!r} is already provided by plugin {other!r}; "
                            f"plugin {plugin!r}'s {self.category} {name!r} is ignored")
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


@dataclass(frozen=True)
class Category:
    """One category of plugin contribution: a row of :data:`CATEGORIES`.

    :param attribute: the registry's attribute on :class:`Registries` and the host.
    :param hook: the registration hook that fills it (specified in :mod:`.hookspecs`).
    :param label: what an item is called in messages (``"robot type"``).
    :param check: ``check(item)``: an error message for an invalid item, else ``None``.
    """

    attribute: str
    hook: str
    label: str
    check: Callable[[Any], str | None]


#: Every category, in registration order: the one table registration is driven by (a new
#: category is a row here and its hook specification in :mod:`.hookspecs`).
CATEGORIES: tuple[Category, ...] = (
    Category("robot_types", "orccad_register_robot_types", "robot type",
             _instance_of(RobotType, "RobotType")),
    Category("control_laws", "orccad_register_control_laws", "control law",
             _instance_of(LawKind, "LawKind")),
    Category("task_functions", "orccad_register_task_functions", "task function",
             _instance_of(TaskFunctionKind, "TaskFunctionKind")),
    Category("trajectories", "orccad_register_trajectories", "trajectory",
             _instance_of(TrajectoryKind, "TrajectoryKind")),
    Category("observers", "orccad_register_observers", "observer", _observer),
    Category("module_kinds", "orccad_register_module_kinds", "module kind",
             _instance_of(ModuleKind, "ModuleKind")),
)


class Registries:
    """One :class:`Registry` per row of :data:`CATEGORIES`, by attribute
    (``registries.robot_types``)."""

    def __init__(self) -> None:
        self._by_attribute: dict[str, Registry[Any]] = {
            c.attribute: Registry(c.label, c.check) for c in CATEGORIES}

    @classmethod
    def empty(cls) -> Registries:
        """Fresh, empty registries with their item checks."""
        return cls()

    def __getattr__(self, attribute: str) -> Registry[Any]:
        try:
            return self.__dict__["_by_attribute"][attribute]
        except KeyError:
            raise AttributeError(attribute) from None

    def __getitem__(self, attribute: str) -> Registry[Any]:
        return self._by_attribute[attribute]

    def all(self) -> list[tuple[str, Registry[Any]]]:
        """``(attribute name, registry)`` pairs in registration order."""
        return list(self._by_attribute.items())

    def remove_plugin(self, plugin: str) -> None:
        """Forget everything ``plugin`` provided, in every registry."""
        for _, registry in self.all():
            registry.remove_plugin(plugin)
