"""Expression nodes of the plan language AST (re-exported by :mod:`orccad_app.lang.ast`).

Also the dataclass decorator every AST node uses: frozen, slotted, keyword-only.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TypeVar, Union, dataclass_transform

from orccad_app.diagnostics import NOWHERE, SourceLocation

__all__ = ["node", "VALUE_TYPES", "PreSignal", "PreValue", "Name", "Number", "String", "Bool", "Vector", "DurationLit",
           "LastValue", "Unary", "Binary", "Arg", "Call", "ParamRef", "Expr"]

_Node = TypeVar("_Node", bound=type)


@dataclass_transform(frozen_default=True, kw_only_default=True)
def node(cls: _Node) -> _Node:
    """The decorator of every AST node class: a frozen, slotted, keyword-only dataclass."""
    return dataclass(frozen=True, slots=True, kw_only=True)(cls)  # type: ignore[return-value]

#: Value types of signals, variables and parameters.
VALUE_TYPES: frozenset[str] = frozenset({"int", "float", "bool", "string", "vector", "duration"})

# --------------------------------------------------------------------------- expressions

@node
class Name:
    """An identifier in an expression: a signal (presence), a variable or a parameter."""

    name: str
    loc: SourceLocation = NOWHERE


@node
class Number:
    """A numeric literal; ``value`` is ``int`` when written without ``.``/exponent.

    A leading minus is folded in (``-0.5`` is ``Number(value=-0.5, text="-0.5")``); the
    constant ``pi`` is ``Number(value=math.pi, text="pi")``.
    """

    value: int | float
    text: str = ""
    loc: SourceLocation = NOWHERE


@node
class String:
    """A string literal, escapes resolved."""

    value: str
    loc: SourceLocation = NOWHERE


@node
class Bool:
    """``true`` or ``false``."""

    value: bool
    loc: SourceLocation = NOWHERE


@node
class Vector:
    """``[e1, e2, ...]``."""

    items: tuple[Expr, ...]
    loc: SourceLocation = NOWHERE


@node
class DurationLit:
    """A duration literal such as ``2.5 s``, in integer nanoseconds."""

    duration_ns: int
    text: str = ""
    loc: SourceLocation = NOWHERE


@node
class LastValue:
    """``?S``: the last value of the valued signal ``S``."""

    signal: str
    loc: SourceLocation = NOWHERE


@node
class Unary:
    """``op operand`` with ``op`` in ``"-"``, ``"not"``."""

    op: str
    operand: Expr
    loc: SourceLocation = NOWHERE


@node
class Binary:
    """``left op right``; ``op`` is one of ``+ - * / < <= > >= == != and or``."""

    op: str
    left: Expr
    right: Expr
    loc: SourceLocation = NOWHERE


@node
class Arg:
    """One argument of a call: ``name = value`` or positional (``name`` is ``None``)."""

    name: str | None
    value: Expr
    loc: SourceLocation = NOWHERE


@node
class Call:
    """``func(args)``: a parameterized kind (law, observer, trajectory...) or function."""

    func: str
    args: tuple[Arg, ...] = ()
    loc: SourceLocation = NOWHERE

    def arg(self, name: str) -> Arg | None:
        """The named argument ``name``, or ``None``."""
        return next((a for a in self.args if a.name == name), None)


@node
class ParamRef:
    """``module.param``: the current value of a Module-Task parameter of the same Robot-Task,
    read only by the value of a type-1 exception (``adjust ctrl.kp = min(ctrl.kp * 1.5,
    800.0)``)."""

    module: str
    param: str
    loc: SourceLocation = NOWHERE


@node
class PreSignal:
    """``pre(S)``: S was present in the previous instant (a presence test)."""

    signal: str
    loc: SourceLocation = NOWHERE


@node
class PreValue:
    """``pre(?S)``: the value of S at the end of the previous instant."""

    signal: str
    loc: SourceLocation = NOWHERE


Expr = Union[Name, Number, String, Bool, Vector, DurationLit, LastValue, PreSignal, PreValue,
             Unary, Binary, Call, ParamRef]
