"""The reaction trees of an automaton as one C ``step`` function: shared nodes, shared blocks.

Every state's reaction tree (:mod:`orccad_app.reactive.automaton`) is a decision tree; the
trees of one automaton repeat the same subtrees many times (the same leaf reached from many
paths, the same action chain under many input tests). :func:`intern` numbers the *distinct*
nodes of all trees, bottom up (two nodes are the same when they are the same kind, test or
action, and their children are the same nodes), so the C code has one labelled line per
distinct node and one function per distinct data action or data test: its size grows with the
distinct blocks, not with the transitions (the paths through the trees).
"""

from __future__ import annotations

from dataclasses import dataclass

from orccad_app.reactive import ir
from orccad_app.reactive.automaton import Action, DataBranch, InputTest, Leaf, Node

__all__ = ["Graph", "GNode", "intern", "ActionRef"]


@dataclass(frozen=True)
class ActionRef:
    """A distinct data action: ``kind`` (``assign``/``emit``), its target and expression."""

    kind: str
    target: object
    expr: ir.Expr


@dataclass(frozen=True)
class GNode:
    """A distinct node. ``tag`` is ``leaf``, ``input``, ``data`` or ``action``.

    - leaf: ``leaf`` is the :class:`Leaf` (emitted outputs, status, target);
    - input: ``signal`` and the ``then``/``orelse`` node numbers;
    - data: ``test`` (the data-test number) and ``then``/``orelse``;
    - action: ``action`` (an index into :attr:`Graph.actions`) and ``then`` (the next node).
    """

    tag: str
    leaf: Leaf | None = None
    signal: ir.SignalDecl | None = None
    test: int = -1
    action: int = -1
    then: int = -1
    orelse: int = -1


@dataclass
class Graph:
    """The distinct nodes of an automaton's trees (``roots[state]`` is a node number)."""

    nodes: list[GNode]
    roots: list[int]
    actions: list[ActionRef]
    tests: list[int]  # the data-test numbers used, in order of first use


def intern(trees: tuple[Node, ...]) -> Graph:
    """Number the distinct nodes of ``trees`` (iteratively: trees may be deep)."""
    nodes: list[GNode] = []
    by_key: dict[tuple, int] = {}
    by_id: dict[int, int] = {}
    actions: list[ActionRef] = []
    action_ids: dict[tuple, int] = {}
    tests: dict[int, None] = {}

    def make(key: tuple, node: GNode) -> int:
        number = by_key.get(key)
        if number is None:
            number = by_key[key] = len(nodes)
            nodes.append(node)
        return number

    roots = []
    for tree in trees:
        stack: list[tuple[Node, bool]] = [(tree, False)]
        while stack:
            node, expanded = stack.pop()
            if id(node) in by_id:
                continue
            if isinstance(node, Leaf):
                key: tuple[object, ...] = ("leaf", node.target, tuple(id(s) for s in node.emitted), node.status)
                by_id[id(node)] = make(key, GNode("leaf", leaf=node))
                continue
            children = ([node.next] if isinstance(node, Action)
                        else [node.then, node.orelse])
            if not expanded:
                stack.append((node, True))
                stack.extend((c, False) for c in children if id(c) not in by_id)
                continue
            numbers = [by_id[id(c)] for c in children]
            if isinstance(node, InputTest):
                key = ("input", id(node.signal), *numbers)
                gnode = GNode("input", signal=node.signal, then=numbers[0], orelse=numbers[1])
            elif isinstance(node, DataBranch):
                tests.setdefault(node.number)
                key = ("data", node.number, *numbers)
                gnode = GNode("data", test=node.number, then=numbers[0], orelse=numbers[1])
            else:
                assert isinstance(node, Action)
                akey = (node.kind, id(node.target), id(node.expr))
                index = action_ids.get(akey)
                if index is None:
                    index = action_ids[akey] = len(actions)
                    actions.append(ActionRef(node.kind, node.target, node.expr))
                key = ("action", index, numbers[0])
                gnode = GNode("action", action=index, then=numbers[0])
            by_id[id(node)] = make(key, gnode)
        roots.append(by_id[id(tree)])
    return Graph(nodes, roots, actions, list(tests))
