"""Temporal-logic nodes of the plan language AST: formulas, properties, assumptions
(re-exported by :mod:`orccad_app.lang.ast`)."""

from __future__ import annotations

from typing import Union

from orccad_app.diagnostics import NOWHERE, SourceLocation
from orccad_app.lang.ast_expr import node

__all__ = ["FSignal", "FPredicate", "FStatus", "FBool", "FUnary", "FBinary", "FCompare",
           "Interval", "SPort", "SNumber", "SCall", "SNeg", "SArith", "SignalExpr", "Formula",
           "Property", "Assumption", "is_signal_formula", "formula_nodes", "SIGNAL_FUNCTIONS"]

#: Functions of signal expressions: name -> (arity, takes a vector).
SIGNAL_FUNCTIONS: dict[str, tuple[int, bool]] = {"norm": (1, True), "abs": (1, False),
                                                  "sqrt": (1, False)}

# --------------------------------------------------------------------------- temporal logic

@node
class FSignal:
    """A signal name in a formula: present in the instant."""

    name: str
    loc: SourceLocation = NOWHERE


@node
class FPredicate:
    """``active(RT)``, ``started(RT)``, ``ended(RT)`` or ``raised(E)``."""

    predicate: str
    argument: str
    loc: SourceLocation = NOWHERE


@node
class FStatus:
    """``done``, ``failed`` or ``aborted``: the mission's status."""

    status: str
    loc: SourceLocation = NOWHERE


@node
class FBool:
    """``true`` or ``false``."""

    value: bool
    loc: SourceLocation = NOWHERE


@node
class Interval:
    """The time bounds ``[low, high]`` of a bounded operator [s], relative to the instant."""

    low_s: float
    high_s: float
    loc: SourceLocation = NOWHERE


@node
class FUnary:
    """``op f``; op in not, next, always, eventually, never, previously, once, historically.

    ``bounds``: ``always[a, b] f`` (Signal Temporal Logic; always, eventually, never, once,
    historically), ``None`` for the unbounded operator."""

    op: str
    operand: Formula
    loc: SourceLocation = NOWHERE
    bounds: Interval | None = None


@node
class FBinary:
    """``f op g``; op in ``and``, ``or``, ``->``, ``<->``, ``until``, ``since``
    (``bounds``: ``f until[a, b] g``, ``f since[a, b] g``)."""

    op: str
    left: Formula
    right: Formula
    loc: SourceLocation = NOWHERE
    bounds: Interval | None = None


# --------------------------------------------------------------------------- signal atoms

@node
class SPort:
    """``robot.port`` or a component ``robot.port[i]`` (0-based): a port value of a robot."""

    robot: str
    port: str
    index: int | None = None
    loc: SourceLocation = NOWHERE


@node
class SNumber:
    """A numeric constant in a signal expression."""

    value: float
    loc: SourceLocation = NOWHERE


@node
class SCall:
    """``norm(v)``, ``abs(x)``, ``sqrt(x)`` (:data:`SIGNAL_FUNCTIONS`)."""

    func: str
    args: tuple[SignalExpr, ...]
    loc: SourceLocation = NOWHERE


@node
class SNeg:
    """``-x``."""

    operand: SignalExpr
    loc: SourceLocation = NOWHERE


@node
class SArith:
    """``x op y``; op in ``+ - * /``."""

    op: str
    left: SignalExpr
    right: SignalExpr
    loc: SourceLocation = NOWHERE


SignalExpr = Union[SPort, SNumber, SCall, SNeg, SArith]


@node
class FCompare:
    """A signal atom ``x op y``; op in ``< <= > >=``: its robustness is the margin in the
    signals' unit (``y - x`` for ``<``)."""

    op: str
    left: SignalExpr
    right: SignalExpr
    loc: SourceLocation = NOWHERE


Formula = Union[FSignal, FPredicate, FStatus, FBool, FUnary, FBinary, FCompare]


def formula_nodes(formula: Formula):
    """Every formula node of ``formula`` (not the signal expressions), root first."""
    stack = [formula]
    while stack:
        item = stack.pop()
        yield item
        if isinstance(item, FUnary):
            stack.append(item.operand)
        elif isinstance(item, FBinary):
            stack += [item.right, item.left]


def is_signal_formula(formula: Formula) -> bool:
    """A Signal Temporal Logic formula: it compares signal values or bounds an operator in
    time. Such a property is monitored on runs, not proved by ``orccad check``."""
    return any(isinstance(f, FCompare) or (isinstance(f, (FUnary, FBinary))
                                           and f.bounds is not None)
               for f in formula_nodes(formula))


@node
class Property:
    """``property MISSION.NAME: formula;`` (``mission`` is ``None`` when written
    ``property NAME: ...``: it then applies to every mission of the file)."""

    mission: str | None
    name: str
    formula: Formula
    loc: SourceLocation = NOWHERE


@node
class Assumption:
    """``assume MISSION.NAME: formula;`` - an environment assumption, same syntax."""

    mission: str | None
    name: str
    formula: Formula
    loc: SourceLocation = NOWHERE
