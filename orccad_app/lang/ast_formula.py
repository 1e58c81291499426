"""Temporal-logic nodes of the plan language AST: formulas, properties, assumptions
(re-exported by :mod:`orccad_app.lang.ast`)."""

from __future__ import annotations

from typing import Union

from orccad_app.diagnostics import NOWHERE, SourceLocation
from orccad_app.lang.ast_expr import node

__all__ = ["FSignal", "FPredicate", "FStatus", "FBool", "FUnary", "FBinary", "Formula",
           "Property", "Assumption"]

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
class FUnary:
    """``op f``; op in not, next, always, eventually, never, previously, once, historically."""

    op: str
    operand: Formula
    loc: SourceLocation = NOWHERE


@node
class FBinary:
    """``f op g``; op in ``and``, ``or``, ``->``, ``<->``, ``until``, ``since``."""

    op: str
    left: Formula
    right: Formula
    loc: SourceLocation = NOWHERE


Formula = Union[FSignal, FPredicate, FStatus, FBool, FUnary, FBinary]


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
