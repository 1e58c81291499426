"""The BDD manager of the symbolic checker, and the variables of a mission's circuit.

CUDD through ``dd.cudd`` (binary wheels) when it imports, else ``dd.autoref`` (the same API,
pure Python, slower). A variable is declared once, by name; the order is the order of
declaration (current and next copies of a register side by side, registers and the inputs
their code tests in program order), which keeps the BDDs of parallel branches small.
"""

from __future__ import annotations

from typing import Any, Iterable

try:  # pragma: no cover - which backend is installed
    from dd import cudd as _backend
    BACKEND = "cudd"
except ImportError:  # pragma: no cover
    from dd import autoref as _backend  # type: ignore[no-redef]
    BACKEND = "autoref"

__all__ = ["Manager", "BACKEND", "Node"]

Node = Any
"""A BDD node of the manager (``dd``'s ``Function``)."""


class Manager:
    """A BDD manager with named boolean variables."""

    def __init__(self) -> None:
        self.bdd = _backend.BDD()
        try:  # pragma: no cover - CUDD only
            self.bdd.configure(reordering=False)
        except (AttributeError, TypeError, ValueError):
            pass
        self.true: Node = self.bdd.true
        self.false: Node = self.bdd.false
        self._vars: dict[str, Node] = {}

    def release(self, *holders: object) -> None:
        """Drop every BDD node the ``holders`` (objects or containers) and this manager keep,
        then the manager: CUDD insists that no node outlives it (``dd`` asserts it when the
        manager is freed, also at interpreter exit)."""
        for holder in holders:
            _clear(holder)
        self._vars.clear()
        self.true = self.false = None
        self.bdd = None

    def declare(self, name: str) -> Node:
        """The variable ``name`` (declared at the end of the order the first time)."""
        node = self._vars.get(name)
        if node is None:
            self.bdd.declare(name)
            node = self._vars[name] = self.bdd.var(name)
        return node

    def var(self, name: str) -> Node:
        return self._vars[name]

    def has(self, name: str) -> bool:
        return name in self._vars

    def any(self, nodes: Iterable[Node]) -> Node:
        result = self.false
        for node in nodes:
            result = result | node
        return result

    def all(self, nodes: Iterable[Node]) -> Node:
        result = self.true
        for node in nodes:
            result = result & node
        return result

    def exists(self, names: Iterable[str], node: Node) -> Node:
        names = [n for n in names]
        return self.bdd.exist(names, node) if names else node

    def rename(self, node: Node, mapping: dict[str, str]) -> Node:
        return self.bdd.let(mapping, node) if mapping else node

    def count(self, node: Node, names: Iterable[str]) -> int:
        return int(self.bdd.count(node, nvars=len(list(names)))) if node != self.false else 0

    def support(self, node: Node) -> set[str]:
        return set(self.bdd.support(node))

    def pick(self, node: Node, names: Iterable[str]) -> dict[str, bool]:
        """One assignment of ``names`` satisfying ``node`` (which must not be false); the
        variables the node does not depend on are false."""
        names = list(names)
        point = self.bdd.pick(node, care_vars=set(names) | self.support(node))
        assert point is not None, "pick from an empty set"
        return {name: bool(point.get(name, False)) for name in names}

    def cube(self, values: dict[str, bool]) -> Node:
        result = self.true
        for name, value in values.items():
            result = result & (self._vars[name] if value else ~self._vars[name])
        return result


def _clear(holder: object) -> None:
    """Empty ``holder``'s containers of nodes (its attributes, or itself if a container)."""
    if isinstance(holder, (dict, list)):
        holder.clear()
        return
    for name, value in list(vars(holder).items()):
        if isinstance(value, (dict, list)):
            value.clear()
        setattr(holder, name, None)
