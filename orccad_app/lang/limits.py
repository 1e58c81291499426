"""Numeric and structural limits of the plan language (documented in ``docs/limits.md``).

Checked on the parse tree, before it becomes the AST, so that every literal a later pass
sees is finite and in range, and every pass can recurse over the program safely:

- an integer literal is at most :data:`MAX_INT` (a 64-bit signed integer, as in Esterel's C
  code); integer arithmetic outside ``[MIN_INT, MAX_INT]`` is a run-time error;
- a number is finite (``1e400`` is refused, not read as infinity) and a non-zero literal does
  not underflow to 0;
- a duration is a whole number of nanoseconds in ``[0, MAX_DURATION_NS]`` (one year); a
  Module-Task ``period`` and a Robot-Task's nominal ``duration`` are at least
  :data:`MIN_PERIOD_NS` (1 µs): ``period 0 ms`` and ``duration 0 s`` are refused;
- blocks nest at most :data:`MAX_NESTING` deep and the parse tree (long operator chains
  included) at most :data:`MAX_TREE_DEPTH` deep.
"""

from __future__ import annotations

import math
import sys
from decimal import Decimal, InvalidOperation

from lark import Token, Tree

from orccad_app.diagnostics import OrccadError, SourceLocation

__all__ = ["MAX_INT", "MIN_INT", "MAX_DURATION_NS", "MIN_PERIOD_NS", "MAX_NESTING",
           "MAX_TREE_DEPTH", "RECURSION_LIMIT", "check_tree", "check_int",
           "ensure_recursion_headroom"]

#: Largest integer (literal or value of an ``int`` variable or signal): 2**63 - 1.
MAX_INT = 2**63 - 1
#: Smallest integer value: -2**63.
MIN_INT = -(2**63)
#: Longest duration: one year [ns].
MAX_DURATION_NS = 365 * 24 * 3600 * 10**9
#: Shortest Module-Task period and Robot-Task nominal duration: 1 µs [ns].
MIN_PERIOD_NS = 1_000
#: Deepest nesting of blocks (``{ … }`` inside ``{ … }``).
MAX_NESTING = 100
#: Deepest parse tree (expressions included: a chain of 2000 ``+`` is fine).
MAX_TREE_DEPTH = 4_000

_UNIT_NS = {"s": 10**9, "ms": 10**6, "us": 10**3, "ns": 1}
#: Rules whose DURATION must be at least MIN_PERIOD_NS, with the word for the message.
_AT_LEAST_PERIOD = {"clause_period": "a Module-Task period", "rt_duration":
                    "a Robot-Task's nominal duration", "clause_sporadic":
                    "a sporadic Module-Task's minimum inter-arrival time"}


#: Python recursion limit while a program is processed: the passes recurse over the AST, and
#: the limits above bound its depth (a test runs every command at those bounds).
RECURSION_LIMIT = 25_000


def ensure_recursion_headroom() -> None:
    """Raise Python's recursion limit to :data:`RECURSION_LIMIT` (never lower it)."""
    if sys.getrecursionlimit() < RECURSION_LIMIT:
        sys.setrecursionlimit(RECURSION_LIMIT)


def check_int(value: int, location: SourceLocation | None, what: str = "integer") -> int:
    """``value`` when it fits :data:`MIN_INT`..:data:`MAX_INT`; else a located error."""
    if MIN_INT <= value <= MAX_INT:
        return value
    raise OrccadError(f"{what} overflow: the result is outside [{MIN_INT}, {MAX_INT}] "
                      "(64-bit integers)", location)


def _loc(filename: str, token: Token) -> SourceLocation:
    return SourceLocation(filename, token.line, token.column, token.end_line, token.end_column)


def _int_literal(token: Token, filename: str) -> None:
    digits = str(token).lstrip("0")
    if len(digits) > len(str(MAX_INT)) or (digits and int(digits) > MAX_INT):
        raise OrccadError(f"integer literal out of range (at most {MAX_INT}; write a "
                          "number with a decimal point for a float)", _loc(filename, token))


def _float_literal(token: Token, filename: str) -> None:
    text = str(token)
    value = float(text)
    if not math.isfinite(value):
        raise OrccadError(f"number {text} is out of range: not finite (at most "
                          f"{sys.float_info.max:.6g})", _loc(filename, token))
    mantissa = text.lower().split("e")[0]
    if value == 0 and mantissa.strip("0.") != "":
        raise OrccadError(f"number {text} is too small: it would be read as 0",
                          _loc(filename, token))


def _duration_literal(token: Token, rule: str | None, filename: str) -> None:
    body = str(token).rstrip()
    unit = next(u for u in ("ms", "us", "ns", "s") if body.endswith(u))
    shown = " ".join(str(token).split())
    try:
        number = Decimal(body[: -len(unit)].strip())
    except InvalidOperation:  # pragma: no cover - the lexer only lets numbers through
        raise OrccadError(f"bad duration '{shown}'", _loc(filename, token)) from None
    limit = Decimal(MAX_DURATION_NS) / _UNIT_NS[unit]
    if number > limit:
        raise OrccadError(f"duration '{shown}' is longer than one year (the longest "
                          "duration)", _loc(filename, token))
    if rule in _AT_LEAST_PERIOD and number * _UNIT_NS[unit] < MIN_PERIOD_NS:
        raise OrccadError(f"{_AT_LEAST_PERIOD[rule]} must be at least 1 us, got '{shown}'",
                          _loc(filename, token))


def _check_token(token: Token, rule: str | None, filename: str) -> None:
    if token.type == "INT":
        _int_literal(token, filename)
    elif token.type == "FLOAT":
        _float_literal(token, filename)
    elif token.type == "DURATION":
        _duration_literal(token, rule, filename)


def _meta_loc(tree: Tree, filename: str) -> SourceLocation:
    meta = tree.meta
    if getattr(meta, "empty", True):
        return SourceLocation(filename, 1, 1)
    return SourceLocation(filename, meta.line, meta.column)


def check_tree(tree: Tree, filename: str) -> None:
    """Raise a located :class:`OrccadError` for the first literal or nesting out of limits.

    Walks ``tree`` iteratively (depth-first, in source order), so it never recurses itself.
    """
    stack: list[tuple[Tree, int, int]] = [(tree, 1, 0)]
    while stack:
        node, depth, blocks = stack.pop()
        if node.data == "block":
            blocks += 1
            if blocks > MAX_NESTING:
                raise OrccadError(f"blocks nested more than {MAX_NESTING} deep (the deepest "
                                  "nesting allowed)", _meta_loc(node, filename))
        if depth > MAX_TREE_DEPTH:
            raise OrccadError(f"expression or statement nested more than {MAX_TREE_DEPTH} "
                              "deep", _meta_loc(node, filename))
        for child in reversed(node.children):
            if isinstance(child, Tree):
                stack.append((child, depth + 1, blocks))
            elif isinstance(child, Token):
                _check_token(child, str(node.data), filename)
