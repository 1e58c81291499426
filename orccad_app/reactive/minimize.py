"""Minimization of an explored automaton by bisimulation, and canonical numbering.

Two control states are bisimilar when their reaction trees are equal once every leaf's target
is replaced by the class of that target. Classes are refined (Moore's algorithm) until stable;
one representative per class is kept and states are numbered breadth first from the initial
state, then-branches first, so the same program always gives the same numbering.
"""

from __future__ import annotations

from collections import deque

from orccad_app.reactive import ir
from orccad_app.reactive.automaton import Action, Automaton, DataBranch, InputTest, Leaf

__all__ = ["minimize"]


def _signature(node, cls: dict) -> tuple:
    if isinstance(node, Leaf):
        return ("L", cls[node.target], node.emitted, node.status)
    if isinstance(node, InputTest):
        return ("I", node.signal, _signature(node.then, cls), _signature(node.orelse, cls))
    if isinstance(node, DataBranch):
        return ("D", node.number, _signature(node.then, cls), _signature(node.orelse, cls))
    return ("A", node.kind, node.target, id(node.expr), _signature(node.next, cls))


def _retarget(node, number: dict):
    if isinstance(node, Leaf):
        return Leaf(number[node.target], node.emitted, node.status)
    if isinstance(node, InputTest):
        return InputTest(node.signal, _retarget(node.then, number), _retarget(node.orelse, number))
    if isinstance(node, DataBranch):
        return DataBranch(node.number, _retarget(node.then, number), _retarget(node.orelse, number))
    return Action(node.kind, node.target, node.expr, _retarget(node.next, number))


def _leaf_targets(node):
    if isinstance(node, Leaf):
        yield node.target
    elif isinstance(node, Action):
        yield from _leaf_targets(node.next)
    else:
        yield from _leaf_targets(node.then)
        yield from _leaf_targets(node.orelse)


def _classes(trees: dict) -> dict:
    cls = {key: 0 for key in trees}
    count = 1
    while True:
        ids: dict[tuple, int] = {}
        refined = {}
        for key, tree in trees.items():
            refined[key] = ids.setdefault(_signature(tree, cls), len(ids))
        if len(ids) == count:
            return refined
        cls, count = refined, len(ids)


def minimize(program: ir.Program, trees: dict, initial, waiting: dict,
             data_tests, variables) -> Automaton:
    """Quotient ``trees`` (control state → reaction tree) by bisimulation."""
    cls = _classes(trees)
    representative: dict[int, object] = {}
    for key in trees:
        representative.setdefault(cls[key], key)
    number: dict[int, int] = {}
    order: list[int] = []
    queue = deque([cls[initial]])
    number[cls[initial]] = 0
    while queue:
        c = queue.popleft()
        order.append(c)
        for target in _leaf_targets(trees[representative[c]]):
            tc = cls[target]
            if tc not in number:
                number[tc] = len(number)
                queue.append(tc)
    state_number = {key: number[cls[key]] for key in trees if cls[key] in number}
    new_trees = tuple(_retarget(trees[representative[c]], state_number) for c in order)
    new_waiting = tuple(waiting[representative[c]] for c in order)
    return Automaton(program, new_trees, new_waiting, tuple(data_tests), tuple(variables))
