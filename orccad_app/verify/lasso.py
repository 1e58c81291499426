"""Direct evaluation of a formula on a lasso: a finite prefix of instants, then a loop
repeated forever.

This is the reference semantics of the logic, used to confirm every counterexample the
checker prints (and by the tests to cross-check the tableau). Each subformula's truth along
the infinite word is itself eventually periodic, so it is computed bottom-up as a
:class:`Periodic` sequence: future operators by a fixpoint around the loop, past operators by
running forward until the pair (position in the loop, carried value) repeats.
"""

from __future__ import annotations

from dataclasses import dataclass
from math import gcd
from typing import Callable, Sequence

from orccad_app.verify.formula import F, subformulas

__all__ = ["Periodic", "evaluate", "holds_on_lasso"]


@dataclass(frozen=True)
class Periodic:
    """The infinite boolean sequence ``pre`` followed by ``loop`` repeated forever."""

    pre: tuple[bool, ...]
    loop: tuple[bool, ...]

    def at(self, i: int) -> bool:
        if i < len(self.pre):
            return self.pre[i]
        return self.loop[(i - len(self.pre)) % len(self.loop)]

    def widened(self, pre_len: int, period: int) -> "Periodic":
        """The same sequence written with a longer prefix and a multiple of the period."""
        total = pre_len + period
        values = self.pre[:total]  # as at(i) for i < total, by slices of pre and loop
        missing = total - len(values)
        if missing > 0:
            loop = self.loop
            values += (loop * (missing // len(loop) + 1))[:missing]
        return Periodic(values[:pre_len], values[pre_len:total])


def _align(a: Periodic, b: Periodic) -> tuple[Periodic, Periodic]:
    pre = max(len(a.pre), len(b.pre))
    period = len(a.loop) * len(b.loop) // gcd(len(a.loop), len(b.loop))
    return a.widened(pre, period), b.widened(pre, period)


def _pointwise(a: Periodic, b: Periodic, op: Callable[[bool, bool], bool]) -> Periodic:
    a, b = _align(a, b)
    return Periodic(tuple(map(op, a.pre, b.pre)), tuple(map(op, a.loop, b.loop)))


def _next(a: Periodic) -> Periodic:
    if a.pre:
        return Periodic(a.pre[1:], a.loop)
    return Periodic((), a.loop[1:] + a.loop[:1])


def _until(a: Periodic, b: Periodic) -> Periodic:
    a, b = _align(a, b)
    n = len(a.loop)
    loop = [False] * n
    for _ in range(n + 1):  # least fixpoint around the loop
        for i in reversed(range(n)):
            loop[i] = b.loop[i] or (a.loop[i] and loop[(i + 1) % n])
    pre = [False] * len(a.pre)
    following = loop[0]
    for i in reversed(range(len(a.pre))):
        pre[i] = following = b.pre[i] or (a.pre[i] and following)
    return Periodic(tuple(pre), tuple(loop))


def _previous(a: Periodic) -> Periodic:
    return Periodic((False,) + a.pre, a.loop)


def _since(a: Periodic, b: Periodic) -> Periodic:
    a, b = _align(a, b)
    values: list[bool] = []
    carried = False
    for i in range(len(a.pre)):
        carried = b.pre[i] or (a.pre[i] and carried)
        values.append(carried)
    n = len(a.loop)
    starts: dict[bool, int] = {}  # value carried into a pass of the loop -> its first index
    while carried not in starts:
        starts[carried] = len(values)
        for i in range(n):
            carried = b.loop[i] or (a.loop[i] and carried)
            values.append(carried)
    first = starts[carried]
    return Periodic(tuple(values[:first]), tuple(values[first:]))


def evaluate(f: F, truth: Callable[[F], Periodic]) -> Periodic:
    """The truth of ``f`` along the word, given ``truth`` of its atoms."""
    value: dict[F, Periodic] = {}
    for g in subformulas(f):
        if g.op == "true" or g.op == "false":
            value[g] = Periodic((), (g.op == "true",))
        elif g.op == "atom":
            value[g] = truth(g)
        elif g.op == "not":
            inner = value[g.left]
            value[g] = Periodic(tuple(not x for x in inner.pre),
                                tuple(not x for x in inner.loop))
        elif g.op == "and":
            value[g] = _pointwise(value[g.left], value[g.right], lambda x, y: x and y)
        elif g.op == "or":
            value[g] = _pointwise(value[g.left], value[g.right], lambda x, y: x or y)
        elif g.op == "X":
            value[g] = _next(value[g.left])
        elif g.op == "U":
            value[g] = _until(value[g.left], value[g.right])
        elif g.op == "Y":
            value[g] = _previous(value[g.left])
        elif g.op == "S":
            value[g] = _since(value[g.left], value[g.right])
        else:  # pragma: no cover - the core has no other operator
            raise ValueError(g.op)
    return value[f]


def holds_on_lasso(f: F, prefix: Sequence[frozenset], loop: Sequence[frozenset]) -> bool:
    """Does ``f`` hold at the first instant of ``prefix + loop^ω``? Letters are sets of atom
    keys true in the instant."""
    if not loop:
        raise ValueError("a lasso needs a non-empty loop")

    def truth(g: F) -> Periodic:
        return Periodic(tuple(g.key in letter for letter in prefix),
                        tuple(g.key in letter for letter in loop))

    return evaluate(f, truth).at(0)
