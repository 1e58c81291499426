"""Data expressions and actions in C: checked arithmetic, the Python runtime's exact errors.

One data action (an assignment or a valued emission) or one data test becomes one static C
function over the automaton's memory: it evaluates the expression into temporaries, in the
order the Python closures of :mod:`orccad_app.reactive.expr` evaluate it (left operand, right
operand, then the operation; ``and``/``or`` short-circuit), and returns ``0`` or the negative
code of the error the Python runtime raises at the same point (:mod:`.errors`): a read of a
value never given, an integer overflow, a division by zero, a non-finite real, vectors of
different sizes, a compiler-made fault. Each error code's message is the Python one.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from orccad_app.codegen.errors import ErrorKind, ErrorTable
from orccad_app.codegen.static_types import ARITHMETIC, BOOL, INT, NEVER, CType, Kind, TypeTable
from orccad_app.lang.limits import MAX_INT, MIN_INT
from orccad_app.reactive import ir
from orccad_app.reactive.expr import divide, format_expr

__all__ = ["Places", "Place", "ExprWriter", "c_type", "c_literal", "c_string", "c_comment",
           "StringTable"]


def _python_message(left: object, right: object) -> str:
    try:
        divide(left, right)
    except ZeroDivisionError as error:
        return str(error)
    raise AssertionError("no division by zero")  # pragma: no cover


#: the messages of the Python runtime (taken from it, so they follow its Python version)
_INT_DIVISION = _python_message(1, 0)
_REAL_DIVISION = _python_message(1.0, 0.0)
_OVERFLOW = f"integer overflow (the result is outside [{MIN_INT}, {MAX_INT}])"


def c_type(ctype: CType) -> str:
    """The C scalar type of ``ctype`` (a vector's element type for a vector)."""
    kind = ctype.element if ctype.kind is Kind.VECTOR else ctype.kind
    return {Kind.INT: "int64_t", Kind.FLOAT: "double", Kind.BOOL: "bool",
            Kind.STRING: "int"}[kind]  # type: ignore[index]


class StringTable:
    """Every string value of the program, numbered in sorted order (so ``<`` on numbers is
    ``<`` on the strings, as Python compares them)."""

    def __init__(self, strings: set[str]) -> None:
        self.names = sorted(strings)
        self.ids = {s: i for i, s in enumerate(self.names)}


def c_literal(value: object, strings: StringTable) -> str:
    """A C literal for a scalar constant."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        if value == MIN_INT:
            return f"(-INT64_C({MAX_INT}) - 1)"
        return f"INT64_C({value})" if value >= 0 else f"(-INT64_C({-value}))"
    if isinstance(value, float):
        text = repr(value)  # shortest round-trip form: a valid C double literal
        return f"({text})" if text.startswith("-") else text
    if isinstance(value, str):
        return str(strings.ids[value])
    raise AssertionError(f"no C literal for {value!r}")


@dataclass(frozen=True)
class Place:
    """A storage place in the memory struct: ``value`` and its ``has`` flag."""

    value: str
    has: str
    ctype: CType


class Places:
    """The C fields of every variable, signal value and ``pre`` value."""

    def __init__(self) -> None:
        self.variables: dict[ir.VarDecl, Place] = {}
        self.values: dict[ir.SignalDecl, Place] = {}
        self.previous: dict[ir.SignalDecl, Place] = {}


@dataclass
class _Value:
    """A computed value: C text (an expression, or the name of an array for a vector)."""

    text: str
    ctype: CType


class ExprWriter:
    """Writes the C body of data actions and data tests (see the module docstring)."""

    def __init__(self, types: TypeTable, places: Places, errors: ErrorTable,
                 strings: StringTable) -> None:
        self.types = types
        self.places = places
        self.errors = errors
        self.strings = strings
        self._lines: list[str] = []
        self._temps = 0
        self._site: ir.Expr | None = None

    # ------------------------------------------------------------------ entry points
    def action(self, kind: str, target: object, expr: ir.Expr) -> list[str]:
        """The body of ``int f(mem *m)`` performing one action."""
        self._begin(expr)
        table = self.places.variables if kind == "assign" else self.places.values
        place = table.get(target)  # type: ignore[call-overload]
        if type(expr) is ir.Const and expr.value is ir.NO_VALUE:
            if place is not None:  # (a place never given a value has no field)
                self._emit(f"{place.has} = false;")
        else:
            value = self._value(expr)
            if value is not None:
                assert place is not None, "a typed value always has its place"
                self._store(place, value)
                self._emit(f"{place.has} = true;")
        self._emit("return 0;")
        return self._lines

    def test(self, expr: ir.Expr) -> list[str]:
        """The body of ``int f(mem *m, bool *r)`` evaluating one data test into ``*r``."""
        self._begin(expr)
        value = self._value(expr)
        if value is not None:
            self._emit(f"*r = {self._truth(value)};")
            self._emit("return 0;")
        return self._lines

    # ------------------------------------------------------------------ machinery
    def _begin(self, site: ir.Expr) -> None:
        self._lines = []
        self._temps = 0
        self._site = site

    def _emit(self, line: str) -> None:
        self._lines.append(line)

    def _temp(self) -> str:
        self._temps += 1
        return f"t{self._temps}"

    def _fail(self, detail: str) -> str:
        """``return CODE;`` for a run-time error of the current site."""
        site = self._site
        assert site is not None
        if type(site) is ir.Fault:
            message = f"run-time error: {detail}"
        else:
            message = f"run-time error in {format_expr(site)}: {detail}"
        code = self.errors.code(ErrorKind.RUNTIME, site.loc, message)
        return f"return {code};"

    def _declare(self, ctype: CType, init: str | None = None) -> str:
        name = self._temp()
        if ctype.kind is Kind.VECTOR:
            self._emit(f"{c_type(ctype)} {name}[{ctype.size}];")
        else:
            self._emit(f"{c_type(ctype)} {name}" + (f" = {init};" if init is not None else ";"))
        return name

    def _store(self, place: Place, value: _Value) -> None:
        if value.ctype.kind is Kind.VECTOR:
            self._emit(f"{{ int i; for (i = 0; i < {value.ctype.size}; ++i) "
                       f"{place.value}[i] = {value.text}[i]; }}")
        else:
            self._emit(f"{place.value} = {value.text};")

    def _truth(self, value: _Value) -> str:
        """Python's ``bool(value)``."""
        kind = value.ctype.kind
        if kind is Kind.BOOL:
            return value.text
        if kind is Kind.INT:
            return f"({value.text} != 0)"
        if kind is Kind.FLOAT:
            return f"({value.text} != 0.0)"
        if kind is Kind.STRING:
            empty = self.strings.ids.get("")
            return "true" if empty is None else f"({value.text} != {empty})"
        return "true"  # a vector has at least one component

    # ------------------------------------------------------------------ expressions
    def _value(self, expr: ir.Expr) -> _Value | None:
        """Emit the evaluation of ``expr``; ``None`` when it always raises (the ``return``
        is emitted; nothing after it runs)."""
        ctype = self.types.of(expr)
        if isinstance(expr, ir.Fault):
            self._emit(self._fail(expr.message))
            return None
        if isinstance(expr, ir.Const):
            return self._const(expr.value, ctype)
        if isinstance(expr, ir.Clock):
            return _Value("m->clock_ns", INT)
        if isinstance(expr, (ir.VarRef, ir.SigValue, ir.PreValue)):
            return self._read(expr)
        if isinstance(expr, ir.VectorExpr):
            items = []
            for item in expr.items:
                value = self._value(item)
                if value is None:
                    return None
                items.append(value.text)
            name = self._declare(ctype)
            for index, text in enumerate(items):
                self._emit(f"{name}[{index}] = {text};")
            return _Value(name, ctype)
        if isinstance(expr, ir.Unary):
            return self._unary(expr, ctype)
        return self._binary(expr, ctype)

    def _const(self, value: object, ctype: CType) -> _Value:
        if ctype.kind is Kind.VECTOR:
            name = self._temp()
            items = ", ".join(c_literal(v, self.strings) for v in value)  # type: ignore[attr-defined]
            self._emit(f"{c_type(ctype)} {name}[{ctype.size}] = {{{items}}};")
            return _Value(name, ctype)
        return _Value(c_literal(value, self.strings), ctype)

    def _read(self, expr: ir.VarRef | ir.SigValue | ir.PreValue) -> _Value | None:
        if isinstance(expr, ir.VarRef):
            place = self.places.variables.get(expr.var)
            detail = f"variable '{expr.var.name}' is read before it is assigned"
        else:
            table = self.places.values if isinstance(expr, ir.SigValue) else self.places.previous
            place = table.get(expr.signal)
            decl = expr.signal
            text = f"?{decl.name}" if isinstance(expr, ir.SigValue) else f"pre(?{decl.name})"
            detail = (f"{text} is read before {decl.name} ever had a value (declare an "
                      f"initial value: 'output {decl.name} : {decl.type} := …;')")
        if place is None:  # never given a value anywhere
            self._emit(self._fail(detail))
            return None
        self._emit(f"if (!{place.has}) {self._fail(detail)}")
        return _Value(place.value, place.ctype)

    def _unary(self, expr: ir.Unary, ctype: CType) -> _Value | None:
        inner = self._value(expr.operand)
        if inner is None:
            return None
        if expr.op == "not":
            return _Value(f"(!{self._truth(inner)})", BOOL)
        if ctype.kind is Kind.VECTOR:
            name = self._declare(ctype)
            self._emit(f"{{ int i; for (i = 0; i < {ctype.size}; ++i) {{")
            self._negate(f"{inner.text}[i]", f"{name}[i]", ctype.element)  # type: ignore[arg-type]
            self._emit("} }")
            return _Value(name, ctype)
        name = self._declare(ctype)
        self._negate(inner.text, name, ctype.kind)
        return _Value(name, ctype)

    def _negate(self, operand: str, result: str, kind: Kind) -> None:
        if kind is Kind.INT:
            self._emit(f"if (ck_neg({operand}, &{result})) {self._fail(_OVERFLOW)}")
        else:
            self._emit(f"{result} = -{operand};")

    def _binary(self, expr: ir.Binary, ctype: CType) -> _Value | None:
        op = expr.op
        left = self._value(expr.left)
        if left is None:
            return None
        if op in ("and", "or"):
            return self._logical(op, left, expr.right)
        right = self._value(expr.right)
        if right is None:
            return None
        if op == "last":
            return right
        if ctype is NEVER:  # vectors of different sizes
            self._emit(self._fail(f"vectors of different sizes ({left.ctype.size} and "
                                  f"{right.ctype.size})"))
            return None
        if op in ("min", "max"):
            name = self._declare(ctype)
            test = "<" if op == "min" else ">"
            self._emit(f"{name} = ({right.text} {test} {left.text}) ? {right.text} : "
                       f"{left.text};")
            return _Value(name, ctype)
        if op in ARITHMETIC:
            return self._arithmetic(op, left, right, ctype)
        return _Value(self._compare(op, left, right), BOOL)

    def _logical(self, op: str, left: _Value, right_expr: ir.Expr) -> _Value:
        name = self._declare(BOOL, self._truth(left))
        self._emit(f"if ({'' if op == 'and' else '!'}{name}) {{")
        right = self._value(right_expr)
        if right is not None:
            self._emit(f"{name} = {self._truth(right)};")
        self._emit("}")
        return _Value(name, BOOL)

    def _arithmetic(self, op: str, left: _Value, right: _Value, ctype: CType) -> _Value:
        if ctype.kind is not Kind.VECTOR:
            name = self._declare(ctype)
            self._scalar(op, left.text, left.ctype.kind, right.text, right.ctype.kind, name,
                         ctype.kind)
            return _Value(name, ctype)
        name = self._declare(ctype)
        a = f"{left.text}[i]" if left.ctype.kind is Kind.VECTOR else left.text
        b = f"{right.text}[i]" if right.ctype.kind is Kind.VECTOR else right.text
        a_kind = left.ctype.element if left.ctype.kind is Kind.VECTOR else left.ctype.kind
        b_kind = right.ctype.element if right.ctype.kind is Kind.VECTOR else right.ctype.kind
        self._emit(f"{{ int i; for (i = 0; i < {ctype.size}; ++i) {{")
        self._scalar(op, a, a_kind, b, b_kind, f"{name}[i]", ctype.element)  # type: ignore[arg-type]
        self._emit("} }")
        return _Value(name, ctype)

    def _scalar(self, op: str, a: str, a_kind: Kind, b: str, b_kind: Kind, result: str,
                kind: Kind) -> None:
        """``result = a op b``, checked as :func:`orccad_app.reactive.expr._checked`."""
        if kind is Kind.INT:
            helper = {"+": "ck_add", "-": "ck_sub", "*": "ck_mul", "/": "ck_div"}[op]
            if op == "/":
                self._emit(f"switch ({helper}({a}, {b}, &{result})) {{ case 1: "
                           f"{self._fail(_OVERFLOW)} case 2: {self._fail(_INT_DIVISION)} "
                           "default: break; }")
            else:
                self._emit(f"if ({helper}({a}, {b}, &{result})) {self._fail(_OVERFLOW)}")
            return
        x = a if a_kind is Kind.FLOAT else f"(double){a}"
        y = b if b_kind is Kind.FLOAT else f"(double){b}"
        if op == "/":
            self._emit(f"if ({y} == 0.0) {self._fail(_REAL_DIVISION)}")
        self._emit(f"{result} = {x} {op} {y};")
        self._emit(f"if (!ck_finite({result})) {{ if ({result} > 0) "
                   f"{self._fail('the result is not a finite number (inf)')} "
                   f"{self._fail('the result is not a finite number (-inf)')} }}")

    def _compare(self, op: str, left: _Value, right: _Value) -> str:
        lk, rk = left.ctype.kind, right.ctype.kind
        if lk is Kind.VECTOR:
            name = self._declare(BOOL, "true")
            if left.ctype.size != right.ctype.size:
                self._emit(f"{name} = false;")
            else:
                equal = self._scalar_compare("==", f"{left.text}[i]", left.ctype.element,
                                             f"{right.text}[i]", right.ctype.element)
                self._emit(f"{{ int i; for (i = 0; i < {left.ctype.size}; ++i) "
                           f"if (!{equal}) {{ {name} = false; break; }} }}")
            return name if op == "==" else f"(!{name})"
        return self._scalar_compare(op, left.text, lk, right.text, rk)

    @staticmethod
    def _scalar_compare(op: str, a: str, a_kind: Kind | None, b: str,
                        b_kind: Kind | None) -> str:
        if a_kind is Kind.INT and b_kind is Kind.FLOAT:
            return f"(cmp_if({a}, {b}) {op} 0)"  # exact, as Python compares int with float
        if a_kind is Kind.FLOAT and b_kind is Kind.INT:
            return f"(0 {op} cmp_if({b}, {a}))"
        return f"({a} {op} {b})"


def _utf8(text: str) -> bytes:
    """The bytes of ``text``: a name read from the file system keeps its undecodable bytes
    (Python holds them as surrogate escapes), any other lone surrogate is written ``\\uXXXX``."""
    try:
        return text.encode("utf-8", "surrogateescape")
    except UnicodeEncodeError:
        return text.encode("utf-8", "backslashreplace")


def c_string(text: str) -> str:
    """A C string literal of ``text`` (its UTF-8 bytes, octal escapes for the rest; a path
    that is not UTF-8 keeps its own bytes)."""
    out = []
    for byte in _utf8(text):
        char = chr(byte)
        if char in '"\\?':
            out.append("\\" + char)
        elif 32 <= byte < 127:
            out.append(char)
        else:
            out.append(f"\\{byte:03o}")
    return '"' + "".join(out) + '"'


def c_comment(text: str) -> str:
    """``text`` made safe inside a C comment on one line: ``/*`` and ``*/`` split (``/ *``,
    ``* /``), ``??`` split (``?\\?``: no trigraph), control characters, line separators and
    bytes that are not UTF-8 written as escapes (``\\n``, ``\\xff``); the rest as it is."""
    decoded = _utf8(text).decode("utf-8", "backslashreplace")
    shown = "".join(char if char.isprintable() else char.encode("unicode_escape").decode("ascii")
                    for char in decoded)
    shown = re.sub(r"/(?=\*)", "/ ", shown)
    shown = re.sub(r"\*(?=/)", "* ", shown)
    return re.sub(r"\?(?=\?)", "?\\\\", shown)
