"""Typed literals written outside a program: one grammar and one wording for every front end.

``orccad react`` input scripts (``S(3.5)``), ``--inject S(value)@T`` and plant faults,
``--set ROBOT.PARAM=VALUE``, the numbers of campaign specs and the values typed in the
terminal UI are read here, by type (the generated ``--main`` program of ``orccad codegen``
reads its scripts in C with the same wording)::

    bool      true | false
    int       a decimal integer as Python's int() reads it, at most 24 characters, within
              64 bits (docs/limits.md)
    float     a number as Python's float() reads it, finite (1e400 and nan are refused);
    duration  the same, in seconds
    vector    finite numbers separated by commas, in brackets ([0.5, 0.5]; [] is empty)
    string    "text" (the text between the quotes, as written)

:func:`read_literal` reads a text as a value of a declared type; :func:`parse_literal`, for
a front end that does not know the type yet (``--inject`` before the plan, ``--set``), reads
it by its form (``true``/``false``, ``"…"``, ``[…]``, else a number) and
:func:`typed_value` later checks it against the type (an ``int`` fits a ``float`` or a
``duration``; nothing else is converted). Every refusal is a :class:`LiteralError` worded by
:func:`refusal` — ``'abc' is not a float value for Gripper (a finite number)`` — a front end
adds only where (a script's line and column, ``--inject X``).
"""

from __future__ import annotations

import math
from typing import Any

from orccad_app.diagnostics import cut
from orccad_app.lang.limits import MAX_INT, MIN_INT

__all__ = ["LiteralError", "HINTS", "read_literal", "parse_literal", "form",
           "typed_value", "literal_text", "refusal"]

#: What a refused value of each type should have been (the refusals' words; ``bool`` and
#: ``string`` say nothing more). ``number`` is an ``int`` or a ``float`` as written,
#: ``scalar`` a number or a ``bool``, ``literal`` any value of the grammar.
HINTS = {
    "int": f"a whole number in [{MIN_INT}, {MAX_INT}]",
    "float": "a finite number",
    "duration": "a finite number",
    "vector": "finite numbers",
    "number": "a finite number",
    "scalar": "a finite number, true or false",
    "literal": 'true, false, a number, [numbers] or "text"',
}

class LiteralError(ValueError):
    """A literal refused: its message is :func:`refusal`'s."""

    def __init__(self, message: str) -> None:
        super().__init__(message)
        self.message = message


def refusal(text: str, type_name: str, name: str | None = None) -> str:
    """``'TEXT' is not a TYPE value[ for NAME][ (HINT)]``: the one wording of a refused
    literal (a long text :func:`~orccad_app.diagnostics.cut`)."""
    where = f" for {name}" if name else ""
    hint = HINTS.get(type_name)
    if type_name == "literal" and _non_finite(text):  # nan, inf, 1e400 read by their form
        hint = "numbers must be finite"
    tail = f" ({hint})" if hint else ""
    return f"'{cut(text)}' is not a {type_name} value{where}{tail}"


def _non_finite(text: str) -> bool:
    try:
        return not math.isfinite(float(text))
    except (ValueError, OverflowError):
        return False


def _finite(text: str) -> float:
    value = float(text)
    if not math.isfinite(value):
        raise ValueError(text)
    return value


def _int(text: str) -> int:
    if len(text) > 24:
        raise ValueError(text)
    value = int(text)
    if not MIN_INT <= value <= MAX_INT:
        raise ValueError(text)
    return value


def _number(text: str) -> int | float:
    try:
        return _int(text)
    except ValueError:
        return _finite(text)


def _read(text: str, type_name: str) -> Any:
    """``text`` (stripped) as a value of ``type_name``; ``ValueError`` if it is not one."""
    if type_name == "bool" or (type_name == "scalar" and text in ("true", "false")):
        if text not in ("true", "false"):
            raise ValueError(text)
        return text == "true"
    if type_name == "string":
        if len(text) < 2 or text[0] != '"' or text[-1] != '"':
            raise ValueError(text)
        return text[1:-1]
    if type_name == "int":
        return _int(text)
    if type_name in ("float", "duration"):
        return _finite(text)
    if type_name == "vector":
        if not (text.startswith("[") and text.endswith("]")):
            raise ValueError(text)
        inner = text[1:-1]
        return tuple(_finite(x) for x in inner.split(",")) if inner.strip() else ()
    if type_name in ("number", "scalar"):
        return _number(text)
    raise ValueError(type_name)


def form(text: str) -> str:
    """The type a literal's form says, for a front end that does not know the declared
    type yet: ``bool`` (``true``, ``false``), ``string`` (``"…"``), ``vector`` (``[…]``),
    else ``number``."""
    text = text.strip()
    if text in ("true", "false"):
        return "bool"
    if text.startswith('"'):
        return "string"
    if text.startswith("[") or text.endswith("]"):
        return "vector"
    return "number"


def read_literal(text: str, type_name: str, name: str | None = None) -> Any:
    """``text`` read as a value of type ``type_name`` (a signal's: ``bool``, ``int``,
    ``float``, ``duration``, ``vector``, ``string``; or ``number``, ``scalar``); raises
    :class:`LiteralError` naming ``name``."""
    text = text.strip()
    try:
        return _read(text, type_name)
    except ValueError:
        raise LiteralError(refusal(text, type_name, name)) from None


def parse_literal(text: str, name: str | None = None) -> Any:
    """``text`` read by its :func:`form`, for :func:`typed_value` to check once the type is
    known; raises :class:`LiteralError`."""
    text = text.strip()
    try:
        return _read(text, form(text))
    except ValueError:
        raise LiteralError(refusal(text, "literal", name)) from None


def literal_text(value: Any) -> str:
    """``value`` written back in the grammar (``true``, ``2.5``, ``[1.0, 2.0]``, ``"dock"``)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return f'"{value}"'
    if isinstance(value, (tuple, list)):
        return "[" + ", ".join(literal_text(v) for v in value) + "]"
    return repr(value)


def _real(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _fits(value: Any, type_name: str) -> Any:
    """``value`` as a value of ``type_name``; ``ValueError`` if it does not fit."""
    if type_name == "bool" and isinstance(value, bool):
        return value
    if type_name == "int" and _real(value) and isinstance(value, int) \
            and MIN_INT <= value <= MAX_INT:
        return value
    if type_name in ("float", "duration") and _real(value) and math.isfinite(value):
        return float(value)
    if type_name in ("number", "scalar") and _real(value) and math.isfinite(value):
        return value
    if type_name == "scalar" and isinstance(value, bool):
        return value
    if type_name == "vector" and isinstance(value, (tuple, list)) \
            and all(_real(v) and math.isfinite(v) for v in value):
        return tuple(float(v) for v in value)
    if type_name == "string" and isinstance(value, str):
        return value
    raise ValueError(type_name)


def typed_value(value: Any, type_name: str, name: str | None = None) -> Any:
    """``value`` (read by :func:`parse_literal`, or given by a program) as a value of type
    ``type_name``; raises :class:`LiteralError` showing it written back
    (:func:`literal_text`) and naming ``name``."""
    try:
        return _fits(value, type_name)
    except ValueError:
        raise LiteralError(refusal(literal_text(value), type_name, name)) from None
