"""Emptiness of model × tableau: a fair accepting lasso, found on the fly.

Product nodes are ``(model state, previous bits, guess)``; an edge is one instant (a model
step, one of its letters, one consistent guess) and carries a bit mask of the acceptance
sets it belongs to: the tableau's untils first, then the model's fairness sets. A path is
accepted when it visits every set infinitely often, i.e. when it ends in a strongly
connected component whose inner edges cover every set.

The search is Tarjan's algorithm, iterative, over successors generated lazily; each
component is tested as soon as it is complete, so a violation stops the search early.
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass

from orccad_app.verify.letters import Alphabet
from orccad_app.verify.model import Model, Step
from orccad_app.verify.tableau import Tableau

__all__ = ["Instant", "Lasso", "find_lasso"]


@dataclass(frozen=True, slots=True)
class Instant:
    """One instant of a counterexample: the model step and the free inputs taken present."""

    step: Step
    chosen: tuple[str, ...]
    letter: int


@dataclass(frozen=True)
class Lasso:
    """An infinite run: ``prefix`` then ``loop`` forever (``loop`` is never empty)."""

    prefix: tuple[Instant, ...]
    loop: tuple[Instant, ...]
    explored: int  # product nodes explored to find it


class _Product:
    def __init__(self, model: Model, alphabet: Alphabet, tableau: Tableau, fair: bool):
        self.model = model
        self.alphabet = alphabet
        self.tableau = tableau
        self.shift = tableau.acceptance_count
        fairness = model.full_fairness if fair else 0
        self.fair = fair
        self.full = ((1 << self.shift) - 1) | (fairness << self.shift)
        self.nodes: list[tuple] = []
        self.index: dict[tuple, int] = {}
        self.edges: dict[int, list[tuple]] = {}

    def node(self, key: tuple) -> int:
        number = self.index.get(key)
        if number is None:
            number = self.index[key] = len(self.nodes)
            self.nodes.append(key)
        return number

    def expand(self, number: int) -> list[tuple]:
        """Edges ``(target, mask, Instant)`` of a node, made once."""
        found = self.edges.get(number)
        if found is not None:
            return found
        state, prev, required = self.nodes[number]
        found = []
        for step in self.model.steps[state]:
            fair = (step.fair << self.shift) if self.fair else 0
            for letter, chosen in self.alphabet.letters(step):
                for guess, carried, accept in self.tableau.successors(letter, prev, required):
                    target = self.node((step.target, carried, guess))
                    found.append((target, accept | fair, Instant(step, chosen, letter)))
        self.edges[number] = found
        return found


def find_lasso(model: Model, alphabet: Alphabet, tableau: Tableau, *,
               fair: bool = True) -> Lasso | None:
    """A run of the model satisfying the tableau's formula (and fairness), or None."""
    product = _Product(model, alphabet, tableau, fair)
    root = product.node((0, 0, None))
    component = _accepting_component(product, root)
    if component is None:
        return None
    return _lasso(product, root, component)


def _accepting_component(product: _Product, root: int) -> set[int] | None:
    index: dict[int, int] = {}
    low: dict[int, int] = {}
    on_stack: set[int] = set()
    stack: list[int] = []
    index[root] = low[root] = 0
    stack.append(root)
    on_stack.add(root)
    work = [(root, iter(product.expand(root)))]
    while work:
        node, edges = work[-1]
        advanced = False
        for target, _, _ in edges:
            if target not in index:
                index[target] = low[target] = len(index)
                stack.append(target)
                on_stack.add(target)
                work.append((target, iter(product.expand(target))))
                advanced = True
                break
            if target in on_stack and index[target] < low[node]:
                low[node] = index[target]
        if advanced:
            continue
        work.pop()
        if work:
            parent = work[-1][0]
            if low[node] < low[parent]:
                low[parent] = low[node]
        if low[node] == index[node]:
            component = set()
            while True:
                member = stack.pop()
                on_stack.discard(member)
                component.add(member)
                if member == node:
                    break
            if _accepting(product, component):
                return component
    return None


def _accepting(product: _Product, component: set[int]) -> bool:
    mask, cyclic = 0, False
    for node in component:
        for target, accept, _ in product.edges[node]:
            if target in component:
                cyclic = True
                mask |= accept
    return cyclic and mask & product.full == product.full


def _path(product: _Product, start: int, goal, inside: set[int] | None) -> list[tuple]:
    """Shortest list of edges from ``start`` to an edge for which ``goal(source, edge)``
    holds (that edge included), staying in ``inside`` when given."""
    parent: dict[int, tuple | None] = {start: None}
    queue = deque([start])
    while queue:
        node = queue.popleft()
        for edge in product.edges.get(node, ()):
            target = edge[0]
            if inside is not None and target not in inside:
                continue
            if goal(node, edge):
                path = [edge]
                while parent[node] is not None:
                    previous, via = parent[node]  # type: ignore[misc]
                    path.append(via)
                    node = previous
                return path[::-1]
            if target not in parent:
                parent[target] = (node, edge)
                queue.append(target)
    raise AssertionError("no path in an explored component")  # pragma: no cover


def _lasso(product: _Product, root: int, component: set[int]) -> Lasso:
    if root in component:
        prefix, entry = [], root
    else:
        prefix = _path(product, root, lambda node, edge: edge[0] in component, None)
        entry = prefix[-1][0]
    loop: list[tuple] = []
    node, missing = entry, product.full
    while missing or not loop:
        wanted = missing
        piece = _path(product, node,
                      lambda src, edge, wanted=wanted: bool(edge[1] & wanted) or not wanted,
                      component)
        loop += piece
        for edge in piece:
            missing &= ~edge[1]
        node = loop[-1][0]
    if node != entry:
        loop += _path(product, node, lambda src, edge: edge[0] == entry, component)
    return Lasso(tuple(e[2] for e in prefix), tuple(e[2] for e in loop), len(product.nodes))
