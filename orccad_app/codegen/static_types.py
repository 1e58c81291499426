"""Static C types for the data of a compiled automaton, inferred from its expressions.

The Python runtime (:mod:`orccad_app.reactive.expr`) is dynamically typed: a variable holds
whatever was last assigned to it. C needs one type per storage place, so this module infers
it and refuses (a located :class:`CodegenError`) what would need a dynamic type:

- a variable or signal given values of two types (``var x := 0; … x := 0.5``: Python then
  prints ``0`` at one instant and ``0.5`` at another; in C ``x`` is one type);
- an operation whose result type depends on the values (``min`` of an int and a float);
- what has no C translation here: string concatenation, order on vectors, arithmetic on
  booleans or strings, comparisons of unrelated types, nested vectors.

Every storage place (a variable, a signal's value, the value a ``pre(?S)`` reads) gets a
:class:`CType`; so does every expression, :data:`NEVER` for one that always raises (a read of
a variable never assigned, a compiler-made fault).
"""

from __future__ import annotations

import enum
from dataclasses import dataclass

from orccad_app.diagnostics import NOWHERE, OrccadError, SourceLocation
from orccad_app.reactive import ir

__all__ = ["Kind", "CType", "INT", "FLOAT", "BOOL", "STRING", "NEVER", "CodegenError",
           "TypeTable", "infer", "const_type", "ARITHMETIC", "COMPARISON", "ORDER"]


class CodegenError(OrccadError):
    """What the generator cannot translate to C (located at the construct)."""


class Kind(enum.Enum):
    """The kinds of C values."""

    INT = "int64_t"
    FLOAT = "double"
    BOOL = "bool"
    STRING = "string"  # an index into the program's string table
    VECTOR = "vector"  # a fixed-size array of INT or FLOAT
    NEVER = "never"    # an expression that always raises


@dataclass(frozen=True)
class CType:
    """A static type: ``kind``, and for a vector its element kind and size."""

    kind: Kind
    element: Kind | None = None
    size: int = 0

    def __str__(self) -> str:
        if self.kind is Kind.VECTOR:
            assert self.element is not None
            return f"vector of {self.size} {_WORD[self.element]}"
        return _WORD[self.kind]


def _a(ctype: CType) -> str:
    text = str(ctype)
    return ("an " if text[0] in "aeiou" else "a ") + text


_WORD = {Kind.INT: "int", Kind.FLOAT: "float", Kind.BOOL: "bool", Kind.STRING: "string",
         Kind.NEVER: "error", Kind.VECTOR: "vector"}

INT, FLOAT, BOOL, STRING, NEVER = (CType(k) for k in (Kind.INT, Kind.FLOAT, Kind.BOOL,
                                                     Kind.STRING, Kind.NEVER))
ARITHMETIC = frozenset({"+", "-", "*", "/"})
ORDER = frozenset({"<", "<=", ">", ">="})
COMPARISON = ORDER | {"==", "!="}
_NUMBERS = (Kind.INT, Kind.FLOAT)


def const_type(value: object, loc: SourceLocation) -> CType:
    """The type of a literal (``NO_VALUE``, the value of a fresh local signal: ``NEVER``)."""
    if value is ir.NO_VALUE:
        return NEVER
    if isinstance(value, bool):
        return BOOL
    if isinstance(value, int):
        return INT
    if isinstance(value, float):
        return FLOAT
    if isinstance(value, str):
        return STRING
    if isinstance(value, tuple):
        kinds = {const_type(v, loc).kind for v in value}
        if not kinds <= set(_NUMBERS) or len(kinds) > 1:
            raise CodegenError("a vector mixing ints and floats (or holding other values) has "
                               "no static C type: write every component as a float", loc)
        element = kinds.pop() if kinds else Kind.FLOAT
        return CType(Kind.VECTOR, element, len(value))
    raise CodegenError(f"a value of Python type {type(value).__name__} has no C type", loc)


def _declared(signal: ir.SignalDecl) -> CType | None:
    """The type the script and the C API give a valued *input* (``None``: inferred)."""
    kind = signal.type
    if kind == "int":
        return INT
    if kind in ("float", "duration"):
        return FLOAT
    if kind == "bool":
        return BOOL
    if kind == "string":
        return STRING
    return None  # a vector: its size comes from the program (see TypeTable.vector_inputs)


class TypeTable:
    """The inferred type of every storage place and of every expression seen."""

    def __init__(self) -> None:
        self.places: dict[object, CType] = {}      # VarDecl / SignalDecl -> type
        self.origin: dict[object, SourceLocation] = {}
        self.exprs: dict[int, CType] = {}          # id(expr) -> type

    def place(self, decl: object) -> CType | None:
        return self.places.get(decl)

    def of(self, expr: ir.Expr) -> CType:
        return self.exprs[id(expr)]

    def give(self, decl: object, ctype: CType, loc: SourceLocation) -> bool:
        """Record that ``decl`` holds values of ``ctype``; True when that is new."""
        if ctype is NEVER:
            return False
        known = self.places.get(decl)
        if known is None:
            self.places[decl] = ctype
            self.origin[decl] = loc
            return True
        if known != ctype:
            what = (f"variable '{decl.name}'" if isinstance(decl, ir.VarDecl)
                    else f"signal {decl.name}")  # type: ignore[attr-defined]
            raise CodegenError(
                f"{what} holds {_a(ctype)} here and {_a(known)} at {self.origin[decl]}: the C code "
                "gives every variable and signal one static type (write the same type "
                "everywhere, e.g. 1.0 for a float)", loc)
        return False


def infer(actions: list[tuple[str, object, ir.Expr]], tests: list[ir.Expr],
          signals: tuple[ir.SignalDecl, ...],
          hints: dict[ir.SignalDecl, CType] | None = None) -> TypeTable:
    """Types of every place and expression of an automaton: ``actions`` are its
    ``(kind, target, expr)`` data actions, ``tests`` its data-test expressions, ``signals``
    its interface (inputs and outputs), ``hints`` types known from elsewhere (the vector
    size of a Robot-Task parameter an output carries)."""
    table = TypeTable()
    for signal, ctype in (hints or {}).items():
        table.give(signal, ctype, signal.loc)
    for signal in signals:
        if signal.init is not None:
            table.give(signal, const_type(signal.init, signal.loc), signal.loc)
        if signal.kind == ir.INPUT and signal.valued:
            declared = _declared(signal)
            if declared is not None:
                table.give(signal, declared, signal.loc)
    changed = True
    while changed:  # each round types more places; a place changes type at most once
        changed = False
        for _kind, target, expr in actions:
            typed = _expr(expr, table, final=False)
            if typed is not None:
                changed |= table.give(target, typed, getattr(expr, "loc", NOWHERE))
            elif (isinstance(expr, (ir.SigValue, ir.PreValue)) and table.place(target) is not None
                  and expr.signal.kind == ir.INPUT):
                # a vector input of no declared size takes the size of where it goes
                changed |= table.give(expr.signal, table.places[target], expr.loc)
    for signal in signals:  # a vector input: its size is the one the program gives it
        if signal.kind == ir.INPUT and signal.valued and signal not in table.places:
            raise CodegenError(
                f"input {signal.name} : {signal.type} has no static size in C: nothing in the "
                "program fixes it (pass it to a Robot-Task parameter with a vector default, "
                "or declare an initial value such as "
                f"'input {signal.name} : vector := [0.0, 0.0, 0.0];')", signal.loc)
        if signal.kind == ir.INPUT and signal.valued:
            ctype = table.places[signal]
            if ctype.kind is Kind.VECTOR and ctype.element is not Kind.FLOAT:
                raise CodegenError(f"input {signal.name}: a script gives vectors of floats, "
                                   "the program an int vector", signal.loc)
    for _kind, _target, expr in actions:
        _expr(expr, table, final=True)
    for expr in tests:
        _expr(expr, table, final=True)
    return table


def _expr(expr: ir.Expr, table: TypeTable, final: bool) -> CType | None:
    """The type of ``expr`` (``None`` while a place it reads is not typed yet); ``final``:
    every place is typed, record the type of each sub-expression and refuse what C lacks."""
    result: CType | None
    if isinstance(expr, ir.Const):
        result = const_type(expr.value, expr.loc)
    elif isinstance(expr, ir.VarRef):
        result = table.place(expr.var)
        if result is None and final:
            result = NEVER  # never assigned: the read always raises
    elif isinstance(expr, (ir.SigValue, ir.PreValue)):
        result = table.place(expr.signal)
        if result is None and final:
            result = NEVER
    elif isinstance(expr, ir.Fault):
        result = NEVER
    elif isinstance(expr, ir.Clock):
        result = INT
    elif isinstance(expr, ir.VectorExpr):
        items = [_expr(i, table, final) for i in expr.items]
        typed = [t for t in items if t is not None]
        result = None if len(typed) < len(items) else _vector(typed, expr.loc)
    elif isinstance(expr, ir.Unary):
        inner = _expr(expr.operand, table, final)
        result = None if inner is None else _unary(expr.op, inner, expr.loc)
    else:
        left = _expr(expr.left, table, final)
        right = _expr(expr.right, table, final)
        result = None if left is None or right is None else _binary(expr.op, left, right,
                                                                     expr.loc)
    if final:
        assert result is not None
        table.exprs[id(expr)] = result
    return result


def _vector(items: list[CType], loc: SourceLocation) -> CType:
    if NEVER in items:
        return NEVER
    kinds = {t.kind for t in items}
    if not kinds <= set(_NUMBERS) or len(kinds) > 1:
        raise CodegenError("a vector mixing ints and floats (or holding other values) has no "
                           "static C type: write every component as a float", loc)
    return CType(Kind.VECTOR, kinds.pop() if kinds else Kind.FLOAT, len(items))


def _unary(op: str, inner: CType, loc: SourceLocation) -> CType:
    if inner is NEVER:
        return NEVER
    if op == "not":
        return BOOL
    if inner.kind in _NUMBERS or inner.kind is Kind.VECTOR:
        return inner
    raise CodegenError(f"'-' on a {inner} has no C translation", loc)


def _binary(op: str, left: CType, right: CType, loc: SourceLocation) -> CType:
    if op in ("and", "or"):
        return BOOL if left is not NEVER else NEVER
    if NEVER in (left, right):
        return NEVER
    if op == "last":
        return right
    if op in ("min", "max"):
        if left != right or left.kind not in _NUMBERS + (Kind.STRING, Kind.BOOL):
            raise CodegenError(f"{op} of {_a(left)} and {_a(right)}: the type of the result would "
                               "depend on the values (write both sides of one type)", loc)
        return left
    if op in COMPARISON:
        _comparable(op, left, right, loc)
        return BOOL
    assert op in ARITHMETIC, op
    if Kind.VECTOR in (left.kind, right.kind):
        return _elementwise(op, left, right, loc)
    if left.kind in _NUMBERS and right.kind in _NUMBERS:
        return INT if left.kind is right.kind is Kind.INT else FLOAT
    raise CodegenError(f"'{op}' on {_a(left)} and {_a(right)} has no C translation", loc)


def _elementwise(op: str, left: CType, right: CType, loc: SourceLocation) -> CType:
    for side in (left, right):
        if side.kind not in _NUMBERS and side.kind is not Kind.VECTOR:
            raise CodegenError(f"'{op}' on {_a(left)} and {_a(right)} has no C translation", loc)
    elements = [t.element if t.kind is Kind.VECTOR else t.kind for t in (left, right)]
    element = Kind.INT if elements == [Kind.INT, Kind.INT] else Kind.FLOAT
    sizes = {t.size for t in (left, right) if t.kind is Kind.VECTOR}
    if len(sizes) > 1:
        return NEVER  # vectors of different sizes: a run-time error wherever evaluated
    return CType(Kind.VECTOR, element, sizes.pop())


def _comparable(op: str, left: CType, right: CType, loc: SourceLocation) -> None:
    if left.kind in _NUMBERS and right.kind in _NUMBERS:
        return
    if left == right and left.kind in (Kind.BOOL, Kind.STRING):
        return
    if op in ("==", "!=") and left.kind is right.kind is Kind.VECTOR:
        return
    raise CodegenError(f"'{op}' between {_a(left)} and {_a(right)} has no C translation", loc)
