"""Temporal formulas in the checker's core form, translated from the plan language's AST.

The core has ``true``, ``false``, atoms, ``not``, ``and``, ``or``, future ``X`` (next) and
``U`` (until), past ``Y`` (previously) and ``S`` (since). Everything else is sugar:

==========================  =====================================
``always f``                ``not (true U not f)``
``eventually f``            ``true U f``
``never f``                 ``always not f``
``once f``                  ``true S f``
``historically f``          ``not (true S not f)``
``f -> g``                  ``not f or g``
``f <-> g``                 ``(not f or g) and (not g or f)``
==========================  =====================================

Nodes are frozen and compare by structure, so equal subformulas are shared (a closure is a
set). An *atom* is a key of the instant's letter (:mod:`orccad_app.verify.letters`):
``("sig", S)``, ``("active", X)``, ``("started", X)``, ``("ended", X)``, ``("raised", E)``,
``("status", s)``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Iterator

from orccad_app.diagnostics import OrccadError
from orccad_app.lang import ast

__all__ = ["F", "TRUE", "FALSE", "atom", "neg", "conj", "disj", "nxt", "until", "prev",
           "since", "from_ast", "subformulas", "atoms", "is_past", "has_past", "format_formula"]

FUTURE_OPS = ("X", "U")
PAST_OPS = ("Y", "S")


@dataclass(frozen=True, slots=True)
class F:
    """A core formula node: ``op`` in true false atom not and or X U Y S."""

    op: str
    left: "F | None" = None
    right: "F | None" = None
    key: tuple | None = None  # the atom's key

    def __repr__(self) -> str:
        return format_formula(self)


TRUE, FALSE = F("true"), F("false")


def atom(key: tuple) -> F:
    return F("atom", key=key)


def neg(f: F) -> F:
    """``not f``, folding constants and double negation."""
    if f.op == "not":
        return f.left  # type: ignore[return-value]
    if f is TRUE or f.op == "true":
        return FALSE
    if f.op == "false":
        return TRUE
    return F("not", f)


def conj(a: F, b: F) -> F:
    if a.op == "false" or b.op == "false":
        return FALSE
    if a.op == "true":
        return b
    if b.op == "true":
        return a
    return F("and", a, b)


def disj(a: F, b: F) -> F:
    if a.op == "true" or b.op == "true":
        return TRUE
    if a.op == "false":
        return b
    if b.op == "false":
        return a
    return F("or", a, b)


def nxt(f: F) -> F:
    return F("X", f)


def until(a: F, b: F) -> F:
    return F("U", a, b)


def prev(f: F) -> F:
    return F("Y", f)


def since(a: F, b: F) -> F:
    return F("S", a, b)


def always(f: F) -> F:
    return neg(until(TRUE, neg(f)))


_PREDICATES = {"active", "started", "ended", "raised"}


def from_ast(formula: ast.Formula) -> F:
    """The core form of a parsed formula; its atoms' names were checked by the parser's
    name checker."""
    if isinstance(formula, ast.FSignal):
        return atom(("sig", formula.name))
    if isinstance(formula, ast.FPredicate):
        if formula.predicate not in _PREDICATES:
            raise OrccadError(f"unknown predicate '{formula.predicate}'", formula.loc)
        return atom((formula.predicate, formula.argument))
    if isinstance(formula, ast.FStatus):
        return atom(("status", formula.status))
    if isinstance(formula, ast.FBool):
        return TRUE if formula.value else FALSE
    if isinstance(formula, ast.FCompare) or getattr(formula, "bounds", None) is not None:
        raise OrccadError("a signal property (signal comparison or time bound) is judged on "
                          "runs, not by the model checker", formula.loc)
    if isinstance(formula, ast.FUnary):
        return _unary(formula.op, from_ast(formula.operand), formula)
    if isinstance(formula, ast.FBinary):
        return _binary(formula.op, from_ast(formula.left), from_ast(formula.right), formula)
    raise OrccadError(f"not a temporal formula: {formula!r}")


def _unary(op: str, f: F, where) -> F:
    if op == "not":
        return neg(f)
    if op == "next":
        return nxt(f)
    if op == "always":
        return always(f)
    if op == "eventually":
        return until(TRUE, f)
    if op == "never":
        return always(neg(f))
    if op == "previously":
        return prev(f)
    if op == "once":
        return since(TRUE, f)
    if op == "historically":
        return neg(since(TRUE, neg(f)))
    raise OrccadError(f"unknown temporal operator '{op}'", where.loc)


def _binary(op: str, a: F, b: F, where) -> F:
    if op == "and":
        return conj(a, b)
    if op == "or":
        return disj(a, b)
    if op == "->":
        return disj(neg(a), b)
    if op == "<->":
        return conj(disj(neg(a), b), disj(neg(b), a))
    if op == "until":
        return until(a, b)
    if op == "since":
        return since(a, b)
    raise OrccadError(f"unknown temporal operator '{op}'", where.loc)


def subformulas(f: F) -> list[F]:
    """Every distinct subformula, children before parents (the root last)."""
    order: list[F] = []
    seen: set[F] = set()
    stack: list[tuple[F, bool]] = [(f, False)]
    while stack:
        node, expanded = stack.pop()
        if node in seen:
            continue
        if expanded:
            seen.add(node)
            order.append(node)
            continue
        stack.append((node, True))
        for child in (node.right, node.left):
            if child is not None and child not in seen:
                stack.append((child, False))
    return order


def atoms(f: F) -> set[tuple]:
    return {g.key for g in subformulas(f) if g.op == "atom"}  # type: ignore[misc]


def _ops(f: F) -> Iterator[str]:
    return (g.op for g in subformulas(f))


def is_past(f: F) -> bool:
    """No future operator: the value at an instant depends on the history only."""
    return not any(op in FUTURE_OPS for op in _ops(f))


def has_past(f: F) -> bool:
    return any(op in PAST_OPS for op in _ops(f))


_INFIX = {"and": "and", "or": "or", "U": "until", "S": "since"}
_PREFIX = {"not": "not", "X": "next", "Y": "previously"}


def _atom_text(key: tuple) -> str:
    kind, name = key
    if kind == "sig":
        return name
    if kind == "status":
        return name
    return f"{kind}({name})"


def format_formula(f: F) -> str:
    """The formula in plan-language syntax (core operators only)."""
    if f.op in ("true", "false"):
        return f.op
    if f.op == "atom":
        return _atom_text(f.key)  # type: ignore[arg-type]
    if f.op in _PREFIX:
        return f"{_PREFIX[f.op]} {_wrap(f.left)}"
    return f"{_wrap(f.left)} {_INFIX[f.op]} {_wrap(f.right)}"


def _wrap(f: F | None) -> str:
    assert f is not None
    text = format_formula(f)
    return text if f.op in ("true", "false", "atom") else f"({text})"
