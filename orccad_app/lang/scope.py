"""Scopes of mission names, and the signal-or-data classification of conditions.

A mission sees, from the outside in: the file-level ``input``/``output`` signals, the
mission's own, then nested scopes (each :class:`~.ast.Block` for ``var``, each ``signal``
statement for local signals). :func:`classify_condition` decides whether a condition is a
presence test or a data expression once its identifiers are resolved.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass, field

from orccad_app.diagnostics import Diagnostic, OrccadError, SourceLocation
from orccad_app.lang import ast

__all__ = ["expr_children", "NameKind", "ConditionKind", "Binding", "Scope", "Problems", "classify_condition",
           "signal_leaves"]


class NameKind(str, enum.Enum):
    """What an identifier of a mission is bound to."""

    SIGNAL = "signal"      #: a signal (input, output or local): a bare name tests presence
    VARIABLE = "variable"  #: a ``var``: a bare name is its value


class ConditionKind(str, enum.Enum):
    """How a condition of ``if``/``await``/``when``/``each``/``every`` is evaluated."""

    SIGNAL = "signal"  #: presence test: signal names under ``not``/``and``/``or``
    DATA = "data"      #: a value (comparisons, ``?S``, variables, literals)


@dataclass(frozen=True)
class Binding:
    """One declared name: its kind and declaration node."""

    kind: NameKind
    decl: ast.SignalDecl | ast.VarDecl

    @property
    def valued(self) -> bool:
        """A variable, or a signal with a type."""
        return self.kind is NameKind.VARIABLE or self.decl.type is not None


@dataclass
class Scope:
    """A chain of name tables; :meth:`child` opens a nested one."""

    names: dict[str, Binding] = field(default_factory=dict)
    parent: Scope | None = None

    def child(self) -> Scope:
        return Scope(parent=self)

    def lookup(self, name: str) -> Binding | None:
        scope: Scope | None = self
        while scope is not None:
            if name in scope.names:
                return scope.names[name]
            scope = scope.parent
        return None

    def visible(self) -> dict[str, Binding]:
        """Every visible name and its binding (inner declarations win)."""
        chain, scope = [], self
        while scope is not None:
            chain.append(scope)
            scope = scope.parent
        table: dict[str, Binding] = {}
        for level in reversed(chain):
            table.update(level.names)
        return table

    def kinds(self) -> dict[str, NameKind]:
        """Every visible name and its kind."""
        return {name: binding.kind for name, binding in self.visible().items()}


class Problems:
    """Errors and warnings collected by the checks, in the order found."""

    def __init__(self) -> None:
        self.errors: list[OrccadError] = []
        self.warnings: list[Diagnostic] = []

    def warning(self, message: str, location: SourceLocation) -> None:
        self.warnings.append(Diagnostic("warning", message, location))

    def error(self, message: str, location: SourceLocation,
              previous: SourceLocation | None = None, what: str = "previous declaration"):
        notes = () if previous is None else (Diagnostic("note", f"{what} here", previous),)
        self.errors.append(OrccadError(message, location, notes))

    def raise_if_any(self) -> None:
        """Raise the first error; the others ride along as notes."""
        if not self.errors:
            return
        first, *rest = self.errors
        notes = list(first.notes)
        for other in rest:
            notes.append(Diagnostic("error", other.message, other.location))
            notes.extend(other.notes)
        raise OrccadError(first.message, first.location, tuple(notes))


def signal_leaves(expr: ast.Expr) -> tuple[ast.Expr, ...] | None:
    """The leaves of ``expr`` if it is a ``not``/``and``/``or`` tree, else ``None``."""
    if isinstance(expr, ast.Unary) and expr.op == "not":
        return signal_leaves(expr.operand)
    if isinstance(expr, ast.Binary) and expr.op in ("and", "or"):
        left, right = signal_leaves(expr.left), signal_leaves(expr.right)
        return None if left is None or right is None else left + right
    return (expr,)


def _names_in(expr: ast.Expr):
    if isinstance(expr, ast.Name):
        yield expr
    for child in expr_children(expr):
        yield from _names_in(child)


def expr_children(expr: ast.Expr) -> tuple:
    """The direct sub-expressions of ``expr`` (operands, vector items, call arguments)."""
    if isinstance(expr, ast.Unary):
        return (expr.operand,)
    if isinstance(expr, ast.Binary):
        return (expr.left, expr.right)
    if isinstance(expr, ast.Vector):
        return expr.items
    if isinstance(expr, ast.Call):
        return tuple(a.value for a in expr.args)
    return ()


def classify_condition(expr: ast.Expr, scope: dict[str, NameKind] | Scope) -> ConditionKind:
    """Whether ``expr`` tests signal presence or computes a value.

    ``scope`` maps visible names to their :class:`NameKind` (or is a :class:`Scope`). A
    condition whose identifiers are all signals (or ``pre(S)``) and whose operators are only
    ``not``, ``and``, ``or`` is :attr:`ConditionKind.SIGNAL`; one naming no signal is
    :attr:`ConditionKind.DATA`. Raises :class:`OrccadError` for a mix of both (``S and
    x > 2``) and for a signal used inside a value (``S + 1``).
    """
    kinds = scope.kinds() if isinstance(scope, Scope) else scope
    signals = [n for n in _names_in(expr) if kinds.get(n.name) is NameKind.SIGNAL]
    leaves = signal_leaves(expr) or ()
    if not signals:
        if leaves and all(isinstance(leaf, ast.PreSignal) for leaf in leaves):
            return ConditionKind.SIGNAL  # pre(S), not pre(A) and pre(B)...: presence tests
        return ConditionKind.DATA
    buried = [n for n in signals if not any(leaf is n for leaf in leaves)]
    if buried:
        raise OrccadError(f"signal '{buried[0].name}' used as a value; write "
                          f"?{buried[0].name} for its last value", buried[0].loc)
    for leaf in leaves:
        if isinstance(leaf, ast.PreSignal):  # pre(S): S's presence in the previous instant
            continue
        if not (isinstance(leaf, ast.Name) and kinds.get(leaf.name) is NameKind.SIGNAL):
            raise OrccadError(f"condition mixes the presence of signal '{signals[0].name}' "
                              "with a value; test them in nested statements", leaf.loc)
    return ConditionKind.SIGNAL
