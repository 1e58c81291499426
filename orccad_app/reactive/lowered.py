"""Reaction trees lowered for execution: tuples and closures, one precomputed result per leaf.

:func:`lower` turns a reaction tree (:mod:`.automaton`) into nested tuples read by
:class:`~orccad_app.reactive.runtime.Reactor` at each instant:

- ``(INPUT, name, then, orelse)`` — a lazily built tree (:mod:`.lazy`) uses a list here, whose
  branches are ``None`` until an instant takes them;
- ``(DATA, test closure, then, orelse, expr)``;
- ``(ACTION, is_assign, target, closure, next, expr)``;
- ``(LEAF, step)`` — ``step`` is the :class:`Step` of that leaf, made once: the lean reaction
  path (:meth:`Reactor.step`) returns it as it is, allocating nothing per instant.
"""

from __future__ import annotations

from dataclasses import dataclass

from orccad_app.reactive import ir
from orccad_app.reactive.automaton import Action, DataBranch, InputTest, Leaf, Node
from orccad_app.reactive.expr import compile_expr
from orccad_app.reactive.status import Status

__all__ = ["Step", "lower", "LEAF", "INPUT", "DATA", "ACTION"]

LEAF, INPUT, DATA, ACTION = range(4)


@dataclass(frozen=True, slots=True)
class Step:
    """What one instant did, shared by every instant that ends at the same leaf.

    :param outputs: names of the outputs emitted, in declaration order.
    :param valued: the valued outputs among them (their values are in the reactor's store:
        :meth:`~orccad_app.reactive.runtime.Reactor.values`).
    :param status: the instant's status (``running``, ``done``, ``failed``, ``aborted``); the
        mission's, which stays ``failed`` once failed, is the reactor's ``status``.
    :param target: the state reached.
    """

    outputs: tuple[str, ...]
    valued: tuple[ir.SignalDecl, ...]
    status: Status
    target: int


def lower(node: Node, data_tests) -> tuple:
    """The executable form of reaction tree ``node`` (leaf targets are state numbers)."""
    if isinstance(node, Leaf):
        names = tuple(s.name for s in node.emitted)
        valued = tuple(s for s in node.emitted if s.valued)
        return (LEAF, Step(names, valued, node.status, node.target))  # type: ignore[arg-type]
    if isinstance(node, InputTest):
        return (INPUT, node.signal.name, lower(node.then, data_tests),
                lower(node.orelse, data_tests))
    if isinstance(node, DataBranch):
        expr = data_tests[node.number].expr
        return (DATA, compile_expr(expr), lower(node.then, data_tests),
                lower(node.orelse, data_tests), expr)
    assert isinstance(node, Action)
    return (ACTION, node.kind == "assign", node.target, compile_expr(node.expr),
            lower(node.next, data_tests), node.expr)
