"""Data expressions: printing and compilation to Python closures.

A compiled expression is a function of a :class:`Store`, the data memory of a running
automaton: variables, last signal values and the clock of the instant in integer nanoseconds.
"""

from __future__ import annotations

import math
import operator
from typing import Any, Callable

from orccad_app.lang.limits import MAX_INT, MIN_INT
from orccad_app.reactive import ir

__all__ = ["Store", "Unset", "compile_expr", "divide", "format_expr", "format_test"]

_BINARY: dict[str, Callable[[Any, Any], Any]] = {
    "+": operator.add, "-": operator.sub, "*": operator.mul,
    "<": operator.lt, "<=": operator.le, ">": operator.gt, ">=": operator.ge,
    "==": operator.eq, "!=": operator.ne, "min": min, "max": max,
    "last": lambda first, second: second,
}


def divide(left: Any, right: Any) -> Any:
    """``/``: integer division truncating toward zero when both sides are integers (as in
    Esterel and C: ``7 / 2`` is 3, ``-7 / 2`` is -3), else real division."""
    if type(left) is int and type(right) is int:
        quotient = abs(left) // abs(right)  # ZeroDivisionError for 0: a run-time error
        return quotient if (left < 0) == (right < 0) else -quotient
    return operator.truediv(left, right)


_BINARY["/"] = divide


def _checked(value: Any) -> Any:
    """An arithmetic result, checked: integers stay within 64 bits, reals finite
    (``docs/limits.md``); else :class:`OverflowError`, reported as a located run-time error."""
    kind = type(value)
    if kind is int and not MIN_INT <= value <= MAX_INT:
        raise OverflowError(f"integer overflow (the result is outside [{MIN_INT}, {MAX_INT}])")
    if kind is float and not math.isfinite(value):
        raise OverflowError(f"the result is not a finite number ({value})")
    return value


_VECTORS = (tuple, list)


def _elementwise(op: Callable[[Any, Any], Any], left: Any, right: Any) -> tuple:
    """``op`` on vectors component by component (a number with a vector: with each
    component); vectors of different sizes are a run-time error."""
    if isinstance(left, _VECTORS) and isinstance(right, _VECTORS):
        if len(left) != len(right):
            raise ValueError(f"vectors of different sizes ({len(left)} and {len(right)})")
        return tuple(_checked(op(a, b)) for a, b in zip(left, right))
    if isinstance(left, _VECTORS):
        return tuple(_checked(op(a, right)) for a in left)
    return tuple(_checked(op(left, b)) for b in right)


def _arithmetic(op: Callable[[Any, Any], Any]) -> Callable[[Any, Any], Any]:
    """``op`` checked (:func:`_checked`), and component-wise on vectors (``+ - * /``)."""
    def apply(left: Any, right: Any) -> Any:
        if isinstance(left, _VECTORS) or isinstance(right, _VECTORS):
            return _elementwise(op, left, right)
        return _checked(op(left, right))
    return apply


def _negate(value: Any) -> Any:
    if isinstance(value, _VECTORS):
        return tuple(_checked(-v) for v in value)
    return _checked(-value)


class Unset(LookupError):
    """A variable or a signal value was read before it was ever given a value."""


class Store:
    """Data memory of a running automaton."""

    __slots__ = ("vars", "values", "clock_ns", "previous")

    def __init__(self) -> None:
        self.vars: dict[ir.VarDecl, Any] = {}
        self.values: dict[ir.SignalDecl, Any] = {}
        self.clock_ns = 0
        #: values at the end of the previous instant, of the signals read by ``pre(?S)``
        self.previous: dict[ir.SignalDecl, Any] = {}


def _var(decl: ir.VarDecl):
    def read(store: Store):
        try:
            return store.vars[decl]
        except KeyError:
            raise Unset(f"variable '{decl.name}' is read before it is assigned") from None
    return read


def _value(decl: ir.SignalDecl, table: str = "values", text: str = "?{0}"):
    def read(store: Store):
        value = getattr(store, table).get(decl, ir.NO_VALUE)
        if value is ir.NO_VALUE:
            raise Unset(f"{text.format(decl.name)} is read before {decl.name} ever had a "
                        "value (declare an initial value: 'output "
                        f"{decl.name} : {decl.type} := …;')")
        return value
    return read


def _fault(expr: ir.Fault):
    message = expr.message

    def fail(store: Store):
        raise Unset(message)
    return fail


def compile_expr(expr: ir.Expr) -> Callable[[Store], Any]:
    """A closure computing ``expr`` from a :class:`Store`."""
    kind = type(expr)
    if kind is ir.Const:
        value = expr.value
        return lambda store: value
    if kind is ir.VarRef:
        return _var(expr.var)
    if kind is ir.SigValue:
        return _value(expr.signal)
    if kind is ir.PreValue:
        return _value(expr.signal, "previous", "pre(?{0})")
    if kind is ir.Fault:
        return _fault(expr)
    if kind is ir.Clock:
        return lambda store: store.clock_ns
    if kind is ir.VectorExpr:
        items = tuple(compile_expr(item) for item in expr.items)
        return lambda store: tuple(f(store) for f in items)
    if kind is ir.Unary:
        inner = compile_expr(expr.operand)
        if expr.op == "-":
            return lambda store: _negate(inner(store))
        return lambda store: not inner(store)
    left, right = compile_expr(expr.left), compile_expr(expr.right)
    if expr.op == "and":
        return lambda store: bool(left(store)) and bool(right(store))
    if expr.op == "or":
        return lambda store: bool(left(store)) or bool(right(store))
    op = _BINARY[expr.op]
    if expr.op in _ARITHMETIC:
        arithmetic = _arithmetic(op)
        return lambda store: arithmetic(left(store), right(store))
    return lambda store: op(left(store), right(store))


_ARITHMETIC = frozenset({"+", "-", "*", "/"})


_PRECEDENCE = {"or": 1, "and": 2, "<": 3, "<=": 3, ">": 3, ">=": 3, "==": 3, "!=": 3,
               "+": 4, "-": 4, "*": 5, "/": 5}


def format_expr(expr: ir.Expr, parent: int = 0) -> str:
    """Source-like text of an expression (the clock prints as ``clock``, in ns)."""
    kind = type(expr)
    if kind is ir.Const:
        return repr(expr.value) if isinstance(expr.value, str) else str(expr.value).lower() \
            if isinstance(expr.value, bool) else str(expr.value)
    if kind is ir.VarRef:
        return expr.var.name
    if kind is ir.SigValue:
        return f"?{expr.signal.name}"
    if kind is ir.PreValue:
        return f"pre(?{expr.signal.name})"
    if kind is ir.Fault:
        return f"error({expr.message!r})"
    if kind is ir.Clock:
        return "clock"
    if kind is ir.VectorExpr:
        return "[" + ", ".join(format_expr(i) for i in expr.items) + "]"
    if kind is ir.Unary:
        sep = " " if expr.op == "not" else ""
        return f"{expr.op}{sep}{format_expr(expr.operand, 6)}"
    if expr.op in ("min", "max", "last"):
        return f"{expr.op}({format_expr(expr.left)}, {format_expr(expr.right)})"
    prec = _PRECEDENCE[expr.op]
    text = f"{format_expr(expr.left, prec)} {expr.op} {format_expr(expr.right, prec + 1)}"
    return f"({text})" if prec < parent else text


def format_test(test: ir.Test) -> str:
    """Source-like text of a presence test or data test."""
    if isinstance(test, ir.SigRef):
        return test.signal.name
    if isinstance(test, ir.PreRef):
        return f"pre({test.signal.name})"
    if isinstance(test, ir.DataTest):
        return format_expr(test.expr)
    if isinstance(test, ir.SigNot):
        return f"not {format_test(test.operand)}"
    op = "and" if isinstance(test, ir.SigAnd) else "or"
    return f"({format_test(test.left)} {op} {format_test(test.right)})"
