"""The data abstraction of the model: which variables are tracked exactly, and evaluation.

A compiled automaton's control states are finite, its data is not. The model keeps:

- *tracked* variables exactly: those whose every assignment is an integer or boolean
  expression of constants and tracked variables with ``+ - *``, comparisons, ``and``,
  ``or``, ``not`` (the counters of ``repeat N`` and ``await N S``, user counters);
- every other value abstractly (:data:`TOP`, "any value"): the clock (timers of
  ``await 2 s``, ``every 1 s``, ``within``, durations, watchdogs), ``?S`` values, floats,
  strings. A data test that reads one is *free*: both outcomes are possible (an
  over-approximation: whatever holds in the model holds in every run).

Tracked variables start at 0 (a well-formed program assigns before it reads).
"""

from __future__ import annotations

import operator
from typing import Any, Callable, Iterable

from orccad_app.reactive import ir
from orccad_app.reactive.circuit_data import is_exact
from orccad_app.reactive.automaton import Action, Automaton, DataBranch, InputTest, Node

__all__ = ["TOP", "tracked_variables", "evaluate", "is_exact", "is_clock_test", "assignments"]


class _Top:
    """Any value (the abstraction of what the model does not track)."""

    _instance = None

    def __new__(cls):
        if cls._instance is None:
            cls._instance = super().__new__(cls)
        return cls._instance

    def __repr__(self) -> str:
        return "TOP"


TOP: Any = _Top()

_ARITH: dict[str, Callable[[Any, Any], Any]] = {
    "+": operator.add, "-": operator.sub, "*": operator.mul,
    "<": operator.lt, "<=": operator.le, ">": operator.gt, ">=": operator.ge,
    "==": operator.eq, "!=": operator.ne,
}


def _nodes(tree: Node) -> Iterable[Node]:
    stack = [tree]
    while stack:
        node = stack.pop()
        yield node
        if isinstance(node, Action):
            stack.append(node.next)
        elif isinstance(node, (InputTest, DataBranch)):
            stack.extend((node.then, node.orelse))


def assignments(automaton: Automaton) -> list[Action]:
    """Every assignment action of the automaton's reaction trees."""
    return [n for tree in automaton.trees for n in _nodes(tree)
            if isinstance(n, Action) and n.kind == "assign"]


def tracked_variables(automaton: Automaton) -> tuple[ir.VarDecl, ...]:
    """The variables the model tracks exactly (a greatest fixpoint), in a stable order."""
    actions = assignments(automaton)
    order: dict[ir.VarDecl, None] = {}
    for action in actions:
        order.setdefault(action.target)
    tracked = set(order)
    changed = True
    while changed:
        changed = False
        for action in actions:
            if action.target in tracked and not is_exact(action.expr, tracked):
                tracked.discard(action.target)
                changed = True
    return tuple(v for v in order if v in tracked)


def evaluate(expr: ir.Expr, env: dict) -> Any:
    """The value of ``expr`` with tracked variables from ``env``, or :data:`TOP`."""
    if isinstance(expr, ir.Const):
        return expr.value if isinstance(expr.value, (bool, int)) else TOP
    if isinstance(expr, ir.VarRef):
        return env.get(expr.var, TOP)
    if isinstance(expr, ir.Unary):
        inner = evaluate(expr.operand, env)
        if inner is TOP:
            return TOP
        return -inner if expr.op == "-" else (not inner) if expr.op == "not" else TOP
    if isinstance(expr, ir.Binary):
        left, right = evaluate(expr.left, env), evaluate(expr.right, env)
        if expr.op == "and":
            return _and(left, right)
        if expr.op == "or":
            return _or(left, right)
        if left is TOP or right is TOP or expr.op not in _ARITH:
            return TOP
        return _ARITH[expr.op](left, right)
    return TOP


def _and(left, right):
    if left is False or right is False:
        return False
    return TOP if left is TOP or right is TOP else bool(left and right)


def _or(left, right):
    if left is True or right is True:
        return True
    return TOP if left is TOP or right is TOP else bool(left or right)


def is_clock_test(expr: ir.Expr) -> bool:
    """Does the test read the clock (a timer: ``clock >= deadline``)?"""
    if isinstance(expr, ir.Clock):
        return True
    if isinstance(expr, ir.Unary):
        return is_clock_test(expr.operand)
    if isinstance(expr, ir.Binary):
        return is_clock_test(expr.left) or is_clock_test(expr.right)
    return False

