"""Run-time arguments of ``run``: which arguments are known at compile time, and their types.

An argument of ``run T(p = e)`` is a *constant* when ``e`` names no variable and reads no
signal value (literals, ``pi``, arithmetic and vectors of those): the compiler evaluates it and
checks the Robot-Task's control scheme with it. Otherwise it is a *run-time argument*
(``run GoTo(target = ?Waypoint)``, ``run Dive(depth = d)``, ``run Track(kp = 400.0 * k)``):
evaluated in the instant the task starts, and checked then. The compiler still checks what it
can see (:func:`argument_problem`): the type of the expression against the parameter's
(``int`` fits a ``float``), and the size of a vector written as a literal against the size of
the parameter's default. A parameter given a run-time argument needs a default: the control
scheme is built and checked with it before the run.
"""

from __future__ import annotations

from dataclasses import dataclass

from orccad_app.lang import ast
from orccad_app.lang.scope import expr_children

__all__ = ["StaticType", "is_constant", "runtime_reads", "static_type", "param_type",
           "argument_problem"]

_NUMERIC = frozenset({"int", "float"})
_COMPARISONS = frozenset({"<", "<=", ">", ">=", "==", "!="})


@dataclass(frozen=True)
class StaticType:
    """What the compiler knows of a value: its type and, for a vector, its size.

    :param type: one of :data:`~orccad_app.lang.ast.VALUE_TYPES`, ``None`` when unknown.
    :param dim: the number of components of a vector, ``None`` when unknown.
    """

    type: str | None = None
    dim: int | None = None

    def text(self) -> str:
        if self.type == "vector" and self.dim is not None:
            return f"vector of {self.dim}"
        return self.type or "unknown"


_UNKNOWN = StaticType()


def runtime_reads(expr: ast.Expr) -> tuple[ast.Expr, ...]:
    """The variables (``Name``) and signal values (``?S``, ``pre(?S)``) ``expr`` reads."""
    if isinstance(expr, (ast.Name, ast.LastValue, ast.PreValue)):
        return (expr,)
    return tuple(leaf for child in expr_children(expr) for leaf in runtime_reads(child))


def is_constant(expr: ast.Expr) -> bool:
    """Whether ``expr`` is known at compile time (reads no variable and no signal value)."""
    return not runtime_reads(expr)


def _literal(expr: ast.Expr) -> StaticType:
    if isinstance(expr, ast.Number):
        return StaticType("int" if isinstance(expr.value, int) else "float")
    if isinstance(expr, ast.String):
        return StaticType("string")
    if isinstance(expr, ast.Bool):
        return StaticType("bool")
    if isinstance(expr, ast.DurationLit):
        return StaticType("duration")
    return _UNKNOWN


def _arithmetic(op: str, left: StaticType, right: StaticType) -> StaticType:
    if "vector" in (left.type, right.type):
        other = right if left.type == "vector" else left
        if other.type == "vector" or other.type in _NUMERIC:
            dims = {t.dim for t in (left, right) if t.type == "vector" and t.dim is not None}
            return StaticType("vector", dims.pop() if len(dims) == 1 else None)
        return _UNKNOWN
    if left.type in _NUMERIC and right.type in _NUMERIC:
        return StaticType("int" if left.type == right.type == "int" else "float")
    if op in "+-" and left.type == right.type == "duration":
        return StaticType("duration")
    return _UNKNOWN


def static_type(expr: ast.Expr, lookup, _depth: int = 0) -> StaticType:
    """The static type of a mission expression; ``lookup(name)`` gives the declaration
    (:class:`~orccad_app.lang.ast.SignalDecl` or :class:`~orccad_app.lang.ast.VarDecl`) a
    name resolves to, or ``None``. An untyped ``var`` has the type of its initial value."""
    if _depth > 32:
        return _UNKNOWN
    if isinstance(expr, (ast.LastValue, ast.PreValue)):
        decl = lookup(expr.signal)
        return StaticType(getattr(decl, "type", None))
    if isinstance(expr, ast.Name):
        decl = lookup(expr.name)
        if isinstance(decl, ast.VarDecl):
            if decl.type is not None:
                return StaticType(decl.type)
            return static_type(decl.value, lookup, _depth + 1)
        return _UNKNOWN
    if isinstance(expr, ast.Vector):
        return StaticType("vector", len(expr.items))
    if isinstance(expr, ast.Unary):
        return StaticType("bool") if expr.op == "not" else \
            static_type(expr.operand, lookup, _depth + 1)
    if isinstance(expr, ast.Binary):
        if expr.op in _COMPARISONS or expr.op in ("and", "or"):
            return StaticType("bool")
        return _arithmetic(expr.op, static_type(expr.left, lookup, _depth + 1),
                           static_type(expr.right, lookup, _depth + 1))
    return _literal(expr)


def param_type(param: ast.Param) -> StaticType:
    """A Robot-Task parameter's type (declared, else its default's) and, for a vector, the
    size of its default when the default is a vector literal."""
    default = StaticType() if param.default is None else static_type(param.default,
                                                                       lambda _: None)
    kind = param.type or default.type
    return StaticType(kind, default.dim if kind == "vector" else None)


def _fits(expected: str, given: str) -> bool:
    if expected == given:
        return True
    return (expected == "float" and given == "int") or (expected == "duration" and given == "int")


def argument_problem(param: ast.Param, expr: ast.Expr, lookup) -> str | None:
    """Why the run-time argument ``expr`` cannot fit ``param``, as far as the compiler can
    see, else ``None``."""
    expected, given = param_type(param), static_type(expr, lookup)
    if param.default is None:
        return (f"parameter '{param.name}' gets a run-time value: give it a default in the "
                "robottask (the control scheme is built and checked with it before the run, "
                "and with the actual value when the task starts)")
    if expected.type is None or given.type is None:
        return None
    if not _fits(expected.type, given.type):
        return (f"parameter '{param.name}' is a {expected.text()}, but this expression is a "
                f"{given.text()}")
    if expected.type == "vector" and None not in (expected.dim, given.dim) \
            and expected.dim != given.dim:
        return (f"parameter '{param.name}' is a vector of {expected.dim} (the size of its "
                f"default), but this expression is a vector of {given.dim}")
    return None

