"""Counters in the circuit: integer and boolean variables as vectors of BDD bits.

The checker tracks exactly the variables whose every assignment is an integer or boolean
expression of constants and tracked variables (``+ - *``, comparisons, ``and or not``: the
counters of ``repeat N``, ``await N S``, a user's counters; :mod:`orccad_app.verify.data`
chooses them). In the circuit each is a register of :data:`WIDTH` bits, two's complement; an
assignment is a multiplexer on its activation, a data test on tracked values a BDD. An
operation whose result leaves the width sets the *overflow* wire: where it can happen in a
reachable state, the checker abstracts the counters instead (as the explicit model does past
its budget).
"""

from __future__ import annotations

from typing import Union

from orccad_app.reactive import ir
from orccad_app.reactive.bdd import Manager, Node

__all__ = ["WIDTH", "Vector", "Arithmetic", "is_exact", "EXACT_OPERATORS"]

#: The binary operators an exact (tracked) expression may use.
EXACT_OPERATORS = frozenset({"+", "-", "*", "<", "<=", ">", ">=", "==", "!=", "and", "or"})


def is_exact(expr: ir.Expr, tracked) -> bool:
    """Can ``expr`` be computed exactly from the ``tracked`` variables (integers, booleans)?"""
    if isinstance(expr, ir.Const):
        return isinstance(expr.value, (bool, int))
    if isinstance(expr, ir.VarRef):
        return expr.var in tracked
    if isinstance(expr, ir.Unary):
        return expr.op in ("-", "not") and is_exact(expr.operand, tracked)
    if isinstance(expr, ir.Binary):
        return (expr.op in EXACT_OPERATORS and is_exact(expr.left, tracked)
                and is_exact(expr.right, tracked))
    return False

#: Bits of a tracked integer: values in [-2^15, 2^15 - 1].
WIDTH = 16

Vector = list
"""A tracked value: its bits, least significant first (a boolean is one bit)."""

Value = Union[Vector, Node]


class Arithmetic:
    """Evaluation of exact expressions on bit vectors; ``overflow`` collects where a result
    leaves :data:`WIDTH` bits (under the activation given to :meth:`evaluate`)."""

    def __init__(self, m: Manager, width: int = WIDTH):
        self.m = m
        self.width = width
        self.overflow: Node = m.false

    # ------------------------------------------------------------------ vectors
    def const(self, value: int) -> Vector:
        m = self.m
        if not -(1 << (self.width - 1)) <= value < (1 << (self.width - 1)):
            self.overflow = m.true
        return [m.true if (value >> i) & 1 else m.false for i in range(self.width)]

    def mux(self, select: Node, then: Vector, orelse: Vector) -> Vector:
        return [(select & a) | (~select & b) for a, b in zip(then, orelse)]

    def _add(self, a: Vector, b: Vector, carry: Node, where: Node) -> Vector:
        out = []
        carry_in_msb = carry
        for i, (x, y) in enumerate(zip(a, b)):
            if i == self.width - 1:
                carry_in_msb = carry
            out.append(_xor(_xor(x, y), carry))
            carry = (x & y) | (carry & _xor(x, y))
        self.overflow |= where & _xor(carry_in_msb, carry)
        return out

    def add(self, a: Vector, b: Vector, where: Node) -> Vector:
        return self._add(a, b, self.m.false, where)

    def sub(self, a: Vector, b: Vector, where: Node) -> Vector:
        return self._add(a, [~x for x in b], self.m.true, where)

    def mul(self, a: Vector, b: Vector, where: Node) -> Vector:
        m = self.m
        wide = 2 * self.width
        ax = a + [a[-1]] * self.width  # sign-extended
        bx = b + [b[-1]] * self.width
        total = [m.false] * wide
        for i in range(wide):
            shifted = [m.false] * i + ax[:wide - i]
            total = _plain_add(total, [bit & bx[i] for bit in shifted])
        result = total[:self.width]
        sign = result[-1]
        for bit in total[self.width:]:
            self.overflow |= where & _xor(bit, sign)
        return result

    def less(self, a: Vector, b: Vector) -> Node:
        """Signed ``a < b``."""
        m = self.m
        lt, eq = m.false, m.true
        for i in reversed(range(self.width)):
            x, y = a[i], b[i]
            if i == self.width - 1:  # the sign bit: a negative, b not
                bit_lt = x & ~y
            else:
                bit_lt = ~x & y
            lt = lt | (eq & bit_lt)
            eq = eq & x.equiv(y)
        return lt

    def equal(self, a: Vector, b: Vector) -> Node:
        return self.m.all(x.equiv(y) for x, y in zip(a, b))

    # ------------------------------------------------------------------ expressions
    def evaluate(self, expr: ir.Expr, values: dict, where: Node) -> Value:
        """The vector (integer) or BDD (boolean) of an exact expression."""
        m = self.m
        if isinstance(expr, ir.Const):
            if isinstance(expr.value, bool):
                return m.true if expr.value else m.false
            return self.const(int(expr.value))
        if isinstance(expr, ir.VarRef):
            return values[expr.var]
        if isinstance(expr, ir.Unary):
            operand = self.evaluate(expr.operand, values, where)
            if expr.op == "not":
                return ~self.truth(operand)
            return self.sub(self.const(0), self.vector(operand), where)
        assert isinstance(expr, ir.Binary)
        left = self.evaluate(expr.left, values, where)
        right = self.evaluate(expr.right, values, where)
        op = expr.op
        if op in ("and", "or"):
            a, b = self.truth(left), self.truth(right)
            return a & b if op == "and" else a | b
        left, right = self.vector(left), self.vector(right)
        # integers (booleans as 0 and 1, as in Python)
        if op == "+":
            return self.add(left, right, where)
        if op == "-":
            return self.sub(left, right, where)
        if op == "*":
            return self.mul(left, right, where)
        if op == "<":
            return self.less(left, right)
        if op == ">":
            return self.less(right, left)
        if op == "<=":
            return ~self.less(right, left)
        if op == ">=":
            return ~self.less(left, right)
        if op == "==":
            return self.equal(left, right)
        if op == "!=":
            return ~self.equal(left, right)
        raise ValueError(f"not an exact operation: {op}")  # pragma: no cover - tracked

    def vector(self, value: Value) -> Vector:
        """An integer's bits (a boolean is 0 or 1, as in Python)."""
        if isinstance(value, list):
            return value
        return [value] + [self.m.false] * (self.width - 1)

    def truth(self, value: Value) -> Node:
        """Where a value is true (an integer: where it is not 0, as in Python)."""
        return self.m.any(value) if isinstance(value, list) else value


def _plain_add(a: Vector, b: Vector) -> Vector:
    out = []
    carry = None
    for x, y in zip(a, b):
        if carry is None:
            out.append(_xor(x, y))
            carry = x & y
        else:
            out.append(_xor(_xor(x, y), carry))
            carry = (x & y) | (carry & _xor(x, y))
    return out


def _xor(a: Node, b: Node) -> Node:
    return ~a.equiv(b)
