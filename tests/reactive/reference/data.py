"""Data of the reference: the binary operators (component by component on vectors) and the
memory of variables, signal values and the clock."""

from __future__ import annotations

import operator
from dataclasses import dataclass, field

__all__ = ["BINARY", "Memory"]

BINARY = {
    "+": operator.add, "-": operator.sub, "*": operator.mul, "/": operator.truediv,
    "<": operator.lt, "<=": operator.le, ">": operator.gt, ">=": operator.ge,
    "==": operator.eq, "!=": operator.ne, "min": min, "max": max,
    "last": lambda first, second: second,
}


def _componentwise(op):
    """Arithmetic on vectors, component by component (a number with each component)."""
    def apply(left, right):
        vectors = (tuple, list)
        if isinstance(left, vectors) and isinstance(right, vectors):
            if len(left) != len(right):
                raise ValueError("vectors of different sizes")
            return tuple(op(a, b) for a, b in zip(left, right))
        if isinstance(left, vectors):
            return tuple(op(a, right) for a in left)
        if isinstance(right, vectors):
            return tuple(op(left, b) for b in right)
        return op(left, right)
    return apply


for _op in ("+", "-", "*", "/"):
    BINARY[_op] = _componentwise(BINARY[_op])


@dataclass
class Memory:
    """Data: variables, last values of valued signals, the clock."""

    vars: dict = field(default_factory=dict)
    values: dict = field(default_factory=dict)
    clock_ns: int = 0
    previous: dict = field(default_factory=dict)   # pre(?S): values before the instant
    was_present: frozenset = frozenset()            # pre(S): keys present in the last instant

    def copy(self) -> "Memory":
        return Memory(dict(self.vars), dict(self.values), self.clock_ns, self.previous,
                      self.was_present)
