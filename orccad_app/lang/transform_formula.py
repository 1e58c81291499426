"""Transformer rules for the temporal logic: properties, assumptions, formulas, signal atoms.

A mixin of :class:`orccad_app.lang.transform.ToAst`, like :mod:`.transform_rt`: the nodes of
:mod:`.ast_formula` (LTL/MTL formulas, STL comparisons of signal expressions, their time
intervals: checked here finite, not negative and not empty).
"""

from __future__ import annotations

import math

from orccad_app.diagnostics import OrccadError
from orccad_app.lang import ast
from orccad_app.lang.limits import MAX_DURATION_NS
from orccad_app.lang.transform_rt import duration_to_ns, rule as _rule

__all__ = ["FormulaRules"]


def _f_unary(op: str, bounded: bool = False):
    if bounded:
        @_rule
        def method(self, meta, bounds, operand):
            return ast.FUnary(op=op, operand=operand, loc=self.loc(meta), bounds=bounds)
        return method

    @_rule
    def plain(self, meta, operand):
        return ast.FUnary(op=op, operand=operand, loc=self.loc(meta))
    return plain


def _f_binary(op: str, bounded: bool = False):
    if bounded:
        @_rule
        def method(self, meta, left, bounds, right):
            return ast.FBinary(op=op, left=left, right=right, loc=self.loc(meta),
                               bounds=bounds)
        return method

    @_rule
    def plain(self, meta, left, right):
        return ast.FBinary(op=op, left=left, right=right, loc=self.loc(meta))
    return plain


def _f_compare(op: str):
    @_rule
    def method(self, meta, left, right):
        return ast.FCompare(op=op, left=left, right=right, loc=self.loc(meta))
    return method


def _s_arith(op: str):
    @_rule
    def method(self, meta, left, right):
        return ast.SArith(op=op, left=left, right=right, loc=self.loc(meta))
    return method


def _f_predicate(predicate: str):
    @_rule
    def method(self, meta, name):
        return ast.FPredicate(predicate=predicate, argument=str(name), loc=self.loc(meta))
    return method


def _f_status(status: str):
    @_rule
    def method(self, meta):
        return ast.FStatus(status=status, loc=self.loc(meta))
    return method


class FormulaRules:
    """Rules of the ``property`` and ``assume`` part of the grammar (needs ``loc``/``tloc``)."""

    @_rule
    def property_(self, meta, name, formula):
        mission, prop = name
        return ast.Property(mission=mission, name=prop, formula=formula, loc=self.loc(meta))

    @_rule
    def assume(self, meta, name, formula):
        mission, prop = name
        return ast.Assumption(mission=mission, name=prop, formula=formula, loc=self.loc(meta))

    @_rule
    def qualified_name(self, meta, mission, name):
        return (str(mission), str(name))

    @_rule
    def simple_name(self, meta, name):
        return (None, str(name))

    @_rule
    def f_signal(self, meta, token):
        return ast.FSignal(name=str(token), loc=self.tloc(token))

    @_rule
    def f_true(self, meta):
        return ast.FBool(value=True, loc=self.loc(meta))

    @_rule
    def f_false(self, meta):
        return ast.FBool(value=False, loc=self.loc(meta))

    @_rule
    def f_paren(self, meta, formula):
        return formula

    f_done, f_failed, f_aborted = (_f_status(s) for s in ("done", "failed", "aborted"))
    f_active, f_started, f_ended, f_raised = (
        _f_predicate(p) for p in ("active", "started", "ended", "raised"))
    f_not, f_next, f_previously = (_f_unary(op) for op in ("not", "next", "previously"))
    f_always, f_eventually, f_never, f_once, f_historically = (
        _f_unary(op, bounded=True) for op in ("always", "eventually", "never", "once",
                                              "historically"))
    f_iff, f_implies, f_or, f_and = (_f_binary(op) for op in ("<->", "->", "or", "and"))
    f_until, f_since = (_f_binary(op, bounded=True) for op in ("until", "since"))

    # -- signal atoms (STL)

    f_lt, f_le, f_gt, f_ge = (_f_compare(op) for op in ("<", "<=", ">", ">="))
    s_add, s_sub, s_mul, s_div = (_s_arith(op) for op in "+-*/")

    @_rule
    def interval(self, meta, low, high):
        where = self.loc(meta)
        for bound in (low, high):
            if not math.isfinite(bound):
                raise OrccadError(f"time bound {bound} s is not finite", where)
            if bound * 1e9 > MAX_DURATION_NS:  # as a duration: [0, 1e300] is refused
                raise OrccadError(f"time bound {bound:.10g} s is longer than one year "
                                  f"({MAX_DURATION_NS // 10**9} s), as every duration", where)
        if low < 0:
            raise OrccadError(f"time bound {low:g} s is negative: write [a, b] with "
                              "0 <= a <= b", where)
        if high < low:
            raise OrccadError(f"empty time interval [{low:g}, {high:g}]: write [a, b] with "
                              "a <= b", where)
        return ast.Interval(low_s=low, high_s=high, loc=where)

    @_rule
    def s_bound(self, meta, token):
        if token.type == "DURATION":
            return duration_to_ns(str(token), self.tloc(token)) / 1e9
        return float(token)

    @_rule
    def s_port(self, meta, robot, port, index):
        return ast.SPort(robot=str(robot), port=str(port),
                         index=None if index is None else int(index), loc=self.loc(meta))

    @_rule
    def s_number(self, meta, token):
        value = float(token)
        if not math.isfinite(value):
            raise OrccadError(f"number {token} is not finite", self.tloc(token))
        return ast.SNumber(value=value, loc=self.tloc(token))

    @_rule
    def s_pi(self, meta):
        return ast.SNumber(value=math.pi, loc=self.loc(meta))

    @_rule
    def s_call(self, meta, func, *args):
        return ast.SCall(func=str(func), args=tuple(args), loc=self.loc(meta))

    @_rule
    def s_neg(self, meta, operand):
        return ast.SNeg(operand=operand, loc=self.loc(meta))
