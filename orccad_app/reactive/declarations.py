"""Signal declarations lowered to the kernel: a mission's interface (its inputs and outputs,
file-level first) and each declaration's initial value and ``combine`` operator, checked
against its type.
"""

from __future__ import annotations

from orccad_app.diagnostics import OrccadError, SourceLocation
from orccad_app.lang import ast
from orccad_app.reactive import ir

__all__ = ["mission_interface", "signal_decl"]


def _kind(direction: ast.Direction) -> str:
    return {ast.Direction.INPUT: ir.INPUT, ast.Direction.OUTPUT: ir.OUTPUT}.get(direction, ir.LOCAL)


def mission_interface(program: ast.Program, mission: ast.Mission | None) -> tuple[tuple, tuple]:
    """The mission's input and output declarations: file-level first, in source order.

    With ``mission`` None, the file-level declarations only.
    """
    inputs: list[ir.SignalDecl] = []
    outputs: list[ir.SignalDecl] = []
    seen: dict[str, SourceLocation] = {}
    own = mission.signals if mission is not None else ()
    for decl in (*program.signals, *own):
        if decl.name in seen:
            raise OrccadError(f"signal '{decl.name}' is declared twice (first at "
                              f"{seen[decl.name]})", decl.loc)
        seen[decl.name] = decl.loc
        lowered = signal_decl(decl, _kind(decl.direction))
        (inputs if lowered.kind == ir.INPUT else outputs).append(lowered)
    return tuple(inputs), tuple(outputs)


_COMBINE_TYPES = {"+": ("int", "float", "vector", "string"), "*": ("int", "float"),
                  "min": ("int", "float"), "max": ("int", "float"), "and": ("bool",),
                  "or": ("bool",)}


def _constant(e: ast.Expr, kind: str | None):
    """The value of a constant initial-value expression, checked against the type."""
    if isinstance(e, ast.Unary) and e.op == "-" and isinstance(e.operand, ast.Number):
        value = -e.operand.value
    elif isinstance(e, (ast.Number, ast.String, ast.Bool)):
        value = e.value
    elif isinstance(e, ast.Vector) and all(isinstance(i, ast.Number) for i in e.items):
        value = tuple(float(i.value) for i in e.items)
    else:
        raise OrccadError("an initial value must be a constant (a number, string, boolean "
                          "or vector of numbers)", e.loc)
    ok = {"int": lambda v: isinstance(v, int) and not isinstance(v, bool),
          "float": lambda v: isinstance(v, (int, float)) and not isinstance(v, bool),
          "bool": lambda v: isinstance(v, bool), "string": lambda v: isinstance(v, str),
          "vector": lambda v: isinstance(v, tuple), "duration": lambda v: False}
    if kind is None or not ok.get(kind, lambda v: True)(value):
        raise OrccadError(f"initial value {value!r} does not fit the signal's type "
                          f"{kind or '(pure)'}", e.loc)
    return float(value) if kind == "float" else value


def signal_decl(decl: ast.SignalDecl, kind: str) -> ir.SignalDecl:
    """The kernel declaration of ``decl``: initial value and combine operator checked."""
    init = None if decl.init is None else _constant(decl.init, decl.type)
    if decl.combine is not None:
        allowed = _COMBINE_TYPES[decl.combine]
        if decl.type not in allowed:
            raise OrccadError(f"'combine {decl.combine}' needs a signal of type "
                              f"{' or '.join(allowed)}, not {decl.type or 'a pure signal'}",
                              decl.loc)
    return ir.SignalDecl(decl.name, kind, decl.type, decl.loc, init, decl.combine)

