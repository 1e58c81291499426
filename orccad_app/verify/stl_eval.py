"""Robustness of a signal property on a run, in time linear in the run and in the formula.

Every node of :mod:`orccad_app.verify.stl_tree` is evaluated once, as one array over the run's
``n`` samples, in ``O(n)`` whatever its time bounds (Donzé, Ferrère, Maler, *Efficient robust
monitoring for STL*, CAV 2013):

- a bounded ``always`` / ``eventually`` (and the past ``historically`` / ``once``) is a
  sliding-window minimum / maximum. The paper slides Lemire's monotone deque; here the
  equivalent van Herk–Gil-Werman scheme computes it with array operations: the samples are cut
  in blocks of the window's width, each block's running minimum is taken forwards and
  backwards, and the window starting at ``i`` is the minimum of the backward running value at
  ``i`` and the forward one at ``i + width - 1`` — three comparisons per sample, any width;
- ``f until[a, b] g`` is decomposed as in the paper: with ``w = b - a``,
  ``ρ(t) = min(min ρf over [t, t+a), ρ(eventually[0, w] g)(t+a), ρ(f until g)(t+a))`` where
  ``until`` alone is the unbounded until, one backward pass ``u(t) = max(ρg(t), min(ρf(t),
  u(t+1)))``; ``since`` is its mirror. The identities hold exactly in the (min, max) algebra,
  so the values are the values of the textbook definition bit for bit (tested against rtamt,
  whose bounded until costs ``O(n·w²)``).

Finite runs, as the textbook on the samples that exist: a window's part past the run is
ignored, an empty window is ``+inf`` (minimum) or ``-inf`` (maximum); ``next`` at the last
sample and ``previously`` at the first are ``+inf``.

Undefined arithmetic on *any* sample of the run (as rtamt, which computes every sample): a
division by zero, the square root of a negative value, a value that is not a number (an
infinity minus an infinity) raise :class:`~orccad_app.verify.stl_tree.UndefinedRobustness`.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Mapping

import numpy as np

from orccad_app.verify.stl_tree import (
    Call, Const, Direction, Event, Junction, Margin, Node, Not, Shift, SignalTerm,
    UndefinedRobustness, Until, Var, Window)

__all__ = ["evaluate", "sliding", "Evaluation"]

INF = np.inf


def sliding(values: np.ndarray, width: int, minimum: bool) -> np.ndarray:
    """``out[i]`` = the minimum (``minimum``) or maximum of ``values[i : i + width]``, the part
    past the end ignored (van Herk–Gil-Werman, ``O(len(values))`` for any ``width`` ≥ 1)."""
    n = len(values)
    width = min(width, n)
    if width <= 1:
        return values.copy()
    reduce = np.minimum if minimum else np.maximum
    neutral = INF if minimum else -INF
    blocks = -(-(n + width - 1) // width)
    padded = np.full(blocks * width, neutral)
    padded[:n] = values
    grid = padded.reshape(blocks, width)
    forward = reduce.accumulate(grid, axis=1).reshape(-1)
    backward = reduce.accumulate(grid[:, ::-1], axis=1)[:, ::-1].reshape(-1)
    return reduce(backward[:n], forward[width - 1:width - 1 + n])


def _window(values: np.ndarray, low: int, high: int | None, minimum: bool) -> np.ndarray:
    """Future window: ``out[i]`` reduces ``values`` over ``[i + low, i + high]`` (to the end
    when ``high`` is None); empty -> neutral."""
    n = len(values)
    neutral = INF if minimum else -INF
    out = np.full(n, neutral)
    if low >= n:
        return out
    rest = values[low:]
    if high is None:
        reduce = np.minimum if minimum else np.maximum
        out[:n - low] = reduce.accumulate(rest[::-1])[::-1]
    else:
        out[:n - low] = sliding(rest, high - low + 1, minimum)
    return out


def _past(values: np.ndarray, function, *args) -> np.ndarray:
    """A past operator as the future one on the reversed run."""
    return function(values[::-1], *args)[::-1]


def _unbounded_until(left: np.ndarray, right: np.ndarray) -> np.ndarray:
    """``u(t) = max(right(t), min(left(t), u(t + 1)))``, ``u(n) = -inf``: one backward pass."""
    lefts, rights = left.tolist(), right.tolist()
    out = [0.0] * len(lefts)
    following = -INF
    for i in range(len(lefts) - 1, -1, -1):
        value = lefts[i] if lefts[i] < following else following
        if rights[i] > value:
            value = rights[i]
        out[i] = following = value
    return np.asarray(out, dtype=float)


def _until(left: np.ndarray, right: np.ndarray, low: int, high: int | None) -> np.ndarray:
    """Future ``left until[low, high] right`` in O(n) (module docstring)."""
    n = len(left)
    unbounded = _unbounded_until(left, right)
    if high is None and low == 0:
        return unbounded
    reached = unbounded if high is None else \
        np.minimum(_window(right, 0, high - low, minimum=False), unbounded)
    out = np.full(n, -INF)
    if low < n:
        out[:n - low] = reached[low:]
        if low > 0:
            out = np.minimum(out, _window(left, 0, low - 1, minimum=True))
    return out


@dataclass
class Evaluation:
    """One evaluation's inputs and what it noticed: ``overflowed`` when some comparison's
    operand left the finite numbers on some sample."""

    data: Mapping[str, np.ndarray]
    samples_ns: int
    overflowed: bool = False
    _length: int = field(init=False, default=0)

    def __post_init__(self) -> None:
        self._length = len(next(iter(self.data.values())))

    def node(self, node: Node) -> np.ndarray:
        if isinstance(node, Margin):
            left, right = self.term(node.left), self.term(node.right)
            if not (np.all(np.isfinite(left)) and np.all(np.isfinite(right))):
                self.overflowed = True
            with np.errstate(all="ignore"):
                margin = right - left if node.op in ("<", "<=") else left - right
            if np.isnan(margin).any():
                raise UndefinedRobustness("a value that is not a number (an infinity minus an "
                                          "infinity, or a sample that is not a number)")
            return margin
        if isinstance(node, Event):
            return self.data[node.name]
        if isinstance(node, Not):
            return -self.node(node.operand)
        if isinstance(node, Junction):
            left, right = self.node(node.left), self.node(node.right)
            if node.op == "and":
                return np.minimum(left, right)
            if node.op == "or":
                return np.maximum(left, right)
            return np.maximum(-left, right)
        if isinstance(node, Shift):
            inner = self.node(node.operand)
            if node.direction is Direction.FUTURE:
                return np.concatenate((inner[1:], [INF]))
            return np.concatenate(([INF], inner[:-1]))
        if isinstance(node, Window):
            return self._window(node)
        return self._until(node)

    def _steps(self, low_ns: int, high_ns: int | None) -> tuple[int, int | None]:
        """Bounds in samples, at most the run's length (a longer window reads the same)."""
        cap = self._length
        low = min(low_ns // self.samples_ns, cap)
        return low, None if high_ns is None else min(high_ns // self.samples_ns, cap)

    def _window(self, node: Window) -> np.ndarray:
        inner = self.node(node.operand)
        low, high = self._steps(node.low_ns, node.high_ns)
        if node.direction is Direction.FUTURE:
            return _window(inner, low, high, node.minimum)
        return _past(inner, _window, low, high, node.minimum)

    def _until(self, node: Until) -> np.ndarray:
        left, right = self.node(node.left), self.node(node.right)
        low, high = self._steps(node.low_ns, node.high_ns)
        if node.direction is Direction.FUTURE:
            return _until(left, right, low, high)
        return _until(left[::-1], right[::-1], low, high)[::-1]

    def term(self, term: SignalTerm) -> np.ndarray:
        if isinstance(term, Var):
            return self.data[term.name]
        if isinstance(term, Const):
            return np.full(self._length, term.value)
        if isinstance(term, Call):
            arg = self.term(term.arg)
            if term.func == "abs":
                return np.abs(arg)
            if (arg < 0).any():
                raise UndefinedRobustness("the square root of a negative value")
            return np.sqrt(arg)
        left, right = self.term(term.left), self.term(term.right)
        with np.errstate(all="ignore"):
            if term.op == "+":
                return left + right
            if term.op == "-":
                return left - right
            if term.op == "*":
                return left * right
            if (right == 0).any():
                raise UndefinedRobustness("a division by zero")
            return left / right


def evaluate(tree: Node, data: Mapping[str, np.ndarray], period_ns: int) -> float:
    """The robustness at the first sample of ``tree`` on ``data`` (variable -> one value per
    sample, every array of one length ≥ 1; events as ``±inf``), samples ``period_ns`` apart.
    Raises :class:`UndefinedRobustness` (module docstring), and for an infinite result when a
    comparison's operand overflowed (an infinite margin of events is a verdict, an overflow of
    the arithmetic is not)."""
    evaluation = Evaluation(data, period_ns)
    value = float(evaluation.node(tree)[0])
    if np.isinf(value) and evaluation.overflowed:
        raise UndefinedRobustness("an overflow of its arithmetic to ±inf")
    return value
