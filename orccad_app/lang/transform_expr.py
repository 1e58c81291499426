"""Transformer rules for expressions: literals, names, operators, calls and port references.

A mixin of :class:`orccad_app.lang.transform.ToAst`, like :mod:`.transform_rt`: the nodes of
:mod:`.ast_expr`, and the port references (``X.port``) of :mod:`.ast_robottask`.
"""

from __future__ import annotations

import math

from orccad_app.lang import ast
from orccad_app.lang.transform_rt import rule as _rule

__all__ = ["ExpressionRules", "unescape"]

_ESCAPES = {"n": "\n", "t": "\t", "r": "\r", "\\": "\\", '"': '"', "0": "\0"}


def unescape(literal: str) -> str:
    """The value of a string literal as written (quotes included), its escapes resolved."""
    out, chars = [], iter(literal[1:-1])
    for char in chars:
        if char == "\\":
            nxt = next(chars, "")
            out.append(_ESCAPES.get(nxt, nxt))
        else:
            out.append(char)
    return "".join(out)


def _binary(op: str):
    @_rule
    def method(self, meta, left, right):
        return ast.Binary(op=op, left=left, right=right, loc=self.loc(meta))
    return method


class ExpressionRules:
    """Rules of the expressions part of the grammar (needs ``loc``/``tloc``/``ns``)."""

    @_rule
    def name(self, meta, token):
        return ast.Name(name=str(token), loc=self.tloc(token))

    @_rule
    def number(self, meta, token):
        text = str(token)
        value = int(text) if token.type == "INT" else float(text)
        return ast.Number(value=value, text=text, loc=self.tloc(token))

    @_rule
    def duration(self, meta, token):
        return ast.DurationLit(duration_ns=self.ns(token), text=" ".join(str(token).split()),
                               loc=self.tloc(token))

    @_rule
    def string(self, meta, token):
        return ast.String(value=unescape(str(token)), loc=self.tloc(token))

    @_rule
    def true(self, meta):
        return ast.Bool(value=True, loc=self.loc(meta))

    @_rule
    def false(self, meta):
        return ast.Bool(value=False, loc=self.loc(meta))

    @_rule
    def pi(self, meta):
        return ast.Number(value=math.pi, text="pi", loc=self.loc(meta))

    @_rule
    def last_value(self, meta, token):
        return ast.LastValue(signal=str(token), loc=self.loc(meta))

    @_rule
    def pre_signal(self, meta, token):
        return ast.PreSignal(signal=str(token), loc=self.loc(meta))

    @_rule
    def pre_value(self, meta, token):
        return ast.PreValue(signal=str(token), loc=self.loc(meta))

    @_rule
    def vector(self, meta, *items):
        items = () if items == (None,) else items
        return ast.Vector(items=tuple(items), loc=self.loc(meta))

    @_rule
    def call_expr(self, meta, name, args):
        return ast.Call(func=str(name), args=args, loc=self.loc(meta))

    @_rule
    def param_ref(self, meta, module, param):
        return ast.ParamRef(module=str(module), param=str(param), loc=self.loc(meta))

    @_rule
    def paren(self, meta, expr):
        return expr

    @_rule
    def neg(self, meta, operand):
        loc = self.loc(meta)
        if isinstance(operand, ast.Number) and operand.text[:1] != "-":
            return ast.Number(value=-operand.value, text="-" + operand.text, loc=loc)
        return ast.Unary(op="-", operand=operand, loc=loc)

    @_rule
    def not_(self, meta, operand):
        return ast.Unary(op="not", operand=operand, loc=self.loc(meta))

    or_, and_ = _binary("or"), _binary("and")
    lt, le, gt, ge, eq, ne = (_binary(op) for op in ("<", "<=", ">", ">=", "==", "!="))
    add, sub, mul, div = (_binary(op) for op in ("+", "-", "*", "/"))

    @_rule
    def call_args(self, meta, *args):
        return () if args == (None,) else tuple(args)

    @_rule
    def named_arg(self, meta, name, value):
        return ast.Arg(name=str(name), value=value, loc=self.loc(meta))

    @_rule
    def positional_arg(self, meta, value):
        return ast.Arg(name=None, value=value, loc=self.loc(meta))

    @_rule
    def call(self, meta, name, args):
        return ast.Call(func=str(name), args=args, loc=self.loc(meta))

    @_rule
    def observer(self, meta, name, args):
        return ast.Call(func=str(name), args=args or (), loc=self.loc(meta))

    @_rule
    def port_ref(self, meta, component, port):
        return ast.PortRef(component=str(component), port=str(port), loc=self.loc(meta))
