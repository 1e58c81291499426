"""Minimization of an explored automaton by bisimulation, and canonical numbering.

Two control states are bisimilar when their reaction trees are equal once every leaf's target
is replaced by the class of that target. Classes are refined (Moore's algorithm) until stable;
one representative per class is kept and states are numbered breadth first from the initial
state, then-branches first, so the same program always gives the same numbering.
"""

from __future__ import annotations

from collections import deque

from orccad_app.reactive import ir
from orccad_app.reactive.automaton import TERMINAL, Action, Automaton, DataBranch, InputTest, Leaf

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


def _classes(trees: dict, labels: dict | None = None) -> dict:
    """The coarsest partition where states of a class have equal signatures (bisimulation),
    refining the partition by ``labels`` (state → label) when given.

    Moore's refinement, made incremental: a round recomputes only the signatures of the
    states some target of which changed class in the previous round; any other state's
    signature is unchanged, hence equal to its unaffected classmates' (one of them is
    recomputed as the reference). A split class keeps its number for the part that stays, so
    only the states that move make their predecessors dirty. The result is the partition of
    plain Moore refinement, but a chain of n states (a sequential mission) is refined in
    O(n) signatures instead of O(n²): one round per state of the chain, each round touching
    one predecessor instead of every state.
    """
    preds: dict = {key: set() for key in trees}
    for key, tree in trees.items():
        for target in _leaf_targets(tree):
            preds[target].add(key)
    initial: dict = {}
    cls = {key: initial.setdefault(labels[key] if labels else None, len(initial))
           for key in trees}
    members: dict[int, set] = {}
    for key, c in cls.items():
        members.setdefault(c, set()).add(key)
    count = len(initial)
    affected = set(trees)  # round 0: every signature is to be computed
    while affected:
        by_class: dict[int, list] = {}
        for key in affected:
            by_class.setdefault(cls[key], []).append(key)
        moves = []  # groups of states leaving their class, decided on the partition as it was
        for c, touched in by_class.items():
            group = members[c]
            if len(group) == 1:
                continue
            reference = None
            if len(touched) < len(group):  # some member is unaffected: its signature stays
                marked = set(touched)
                other = next(k for k in group if k not in marked)
                reference = _signature(trees[other], cls)
            parts: dict[tuple, list] = {}
            for key in touched:
                sig = _signature(trees[key], cls)
                if sig != reference:
                    parts.setdefault(sig, []).append(key)
            split = list(parts.values())
            if reference is None:
                split = split[1:]  # the first part keeps the class's number
            moves.extend(split)
        affected = set()
        for part in moves:
            new = count
            count += 1
            old = members[cls[part[0]]]
            for key in part:
                old.discard(key)
                cls[key] = new
                affected |= preds[key]
            members[new] = set(part)
    return cls


def minimize(program: ir.Program, trees: dict, initial, waiting: dict, labels: dict,
             data_tests, variables) -> Automaton:
    """Quotient ``trees`` (control state → reaction tree) by bisimulation.

    States with different labels are never merged, so label predicates survive.
    """
    cls = _classes(trees, labels)
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
    # where a class waits: a member's that waits somewhere (the boot state, merged with the
    # states of a loop it starts, waits nowhere; its class waits where the loop does)
    waits: dict[int, tuple] = {}
    for key in trees:
        if waiting[key] and cls[key] not in waits:
            waits[cls[key]] = waiting[key]
    new_waiting = tuple(waits.get(c, waiting[representative[c]]) for c in order)
    new_labels = tuple(labels[representative[c]] for c in order)
    terminal = next((state_number[k] for k in trees if k == TERMINAL and k in state_number), None)
    return Automaton(program, new_trees, new_waiting, tuple(data_tests), tuple(variables),
                     new_labels, terminal)
