"""Expressions as a reaction sees them: the values they read in the instant, and ``pre(?S)``
of a local signal in its first instant.

The IR nodes a reaction makes (substituted expressions, combinations, faults) are made once
per prepared program (:func:`made`), so that equal events of two reactions are the same objects.
"""

from __future__ import annotations

from orccad_app.reactive import ir
from orccad_app.reactive.expr import Store, Unset, compile_expr
from orccad_app.reactive.prepare import Prepared

__all__ = ["is_var", "value_reads", "fresh_pre", "fresh_test", "made"]


def is_var(key) -> bool:
    return type(key) is tuple and key[0] == "var"


def value_reads(expr: ir.Expr, out: list, variables: set = frozenset()) -> list:
    """The signals whose value (``?S``, not ``pre(?S)``) ``expr`` reads, and
    ``("var", v)`` for the variables of ``variables`` it reads."""
    kind = type(expr)
    if kind is ir.SigValue:
        out.append(expr.signal)
    elif kind is ir.VarRef:
        if expr.var in variables:
            out.append(("var", expr.var))
    elif kind is ir.Unary:
        value_reads(expr.operand, out, variables)
    elif kind is ir.Binary:
        value_reads(expr.left, out, variables)
        value_reads(expr.right, out, variables)
    elif kind is ir.VectorExpr:
        for item in expr.items:
            value_reads(item, out, variables)
    return out


def fresh_pre(prep: Prepared, expr: ir.Expr, scope: dict) -> ir.Expr:
    """``expr`` with ``pre(?S)`` of a local signal in its first instant (a fresh incarnation)
    replaced by S's initial value: the fresh signal has no past (Esterel v5)."""
    fresh = [d for d, key in scope.items() if type(key) is tuple and not key[1]]
    if not fresh or not _has_pre(expr, fresh):
        return expr
    return made(prep, ("fresh", id(expr), tuple(id(d) for d in fresh)),
                 lambda: _substitute_pre(expr, fresh))


def fresh_test(prep: Prepared, test: ir.DataTest, scope: dict) -> int | bool:
    """Data test ``test`` as decided in ``scope``: its number, or, when it reads ``pre(?S)``
    of a local signal in its first instant, the test with S's initial value in its place, as
    :func:`fresh_pre` does for emissions and assignments (``if pre(?Internal) == -1`` of
    ``signal Internal : int := -1`` is true in the signal's first instant, HipHop's
    ``preval``): its outcome when it then reads nothing (decided here, as a constant), else
    the number of that test (made once, appended to ``prep.data_tests``)."""
    expr = fresh_pre(prep, test.expr, scope)
    if expr is test.expr:
        return prep.data_test_index[id(test)]

    def make() -> int | bool:
        if _constant(expr):
            try:
                return bool(compile_expr(expr)(Store()))
            except (Unset, ArithmeticError, ValueError):
                pass  # its run-time error, raised when the test is decided
        prep.data_test_index[id(expr)] = len(prep.data_tests)
        prep.data_tests.append(ir.DataTest(expr, test.loc))
        return prep.data_test_index[id(expr)]
    return made(prep, ("fresh test", id(expr)), make)


def _constant(expr: ir.Expr) -> bool:
    """``expr`` reads nothing: no variable, signal value, ``pre``, clock or fault."""
    kind = type(expr)
    if kind is ir.Const:
        return True
    if kind is ir.Unary:
        return _constant(expr.operand)
    if kind is ir.Binary:
        return _constant(expr.left) and _constant(expr.right)
    if kind is ir.VectorExpr:
        return all(_constant(item) for item in expr.items)
    return False


def _has_pre(expr: ir.Expr, decls: list) -> bool:
    kind = type(expr)
    if kind is ir.PreValue:
        return expr.signal in decls
    if kind is ir.Unary:
        return _has_pre(expr.operand, decls)
    if kind is ir.Binary:
        return _has_pre(expr.left, decls) or _has_pre(expr.right, decls)
    if kind is ir.VectorExpr:
        return any(_has_pre(i, decls) for i in expr.items)
    return False


def _substitute_pre(expr: ir.Expr, decls: list) -> ir.Expr:
    kind = type(expr)
    if kind is ir.PreValue and expr.signal in decls:
        if expr.signal.init is None:
            return ir.Fault(f"pre(?{expr.signal.name}) is read in the first instant of local "
                            f"signal {expr.signal.name}, which has no initial value", expr.loc)
        return ir.Const(expr.signal.init, expr.loc)
    if kind is ir.Unary:
        return ir.Unary(expr.op, _substitute_pre(expr.operand, decls), expr.loc)
    if kind is ir.Binary:
        return ir.Binary(expr.op, _substitute_pre(expr.left, decls),
                         _substitute_pre(expr.right, decls), expr.loc)
    if kind is ir.VectorExpr:
        return ir.VectorExpr(tuple(_substitute_pre(i, decls) for i in expr.items), expr.loc)
    return expr


def made(prep: Prepared, key: tuple, make):
    """``prep``'s node for ``key``, made by ``make()`` the first time it is asked for."""
    found = prep.made.get(key)
    if found is None:
        found = prep.made[key] = make()
    return found

