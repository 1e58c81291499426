"""Input scripts for ``orccad react``: one instant per line.

A line lists the input signals present in that instant, separated by spaces; a valued signal
is written ``S(3.5)`` (``S(true)``, ``S("text")``). An empty line is an instant with no input.
Text after ``#`` (outside a string) is a comment; a line holding only a comment is not an
instant. A line may start with ``@T``, T in seconds (absolute, non-decreasing, at most one
year), to set that instant's clock. Values are checked as the language checks literals:
numbers finite, integers within 64 bits (see ``docs/limits.md``)::

    A           # instant 1: A present
    @0.5 B R    # instant 2, at t = 0.5 s
                # (the empty line above is instant 3)
    Battery(17.5)
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import Any

from orccad_app.diagnostics import OrccadError, SourceLocation
from orccad_app.lang.limits import MAX_DURATION_NS
from orccad_app.lang.literals import LiteralError, read_literal
from orccad_app.reactive import ir

__all__ = ["Instant", "parse_script", "parse_value"]

_STRING = r'"(?:[^"\\]|\\.)*"'
_TOKEN = re.compile(r"\s*(?:(@\S*)|([A-Za-z_][A-Za-z0-9_.]*)(\(((?:" + _STRING
                    + r'|[^)"])*)\))?|(\S))')
_COMMENT = re.compile(_STRING + r"|(#)")


def _strip_comment(raw: str) -> str:
    """``raw`` without its comment: the first ``#`` outside a string and what follows."""
    for match in _COMMENT.finditer(raw):
        if match.group(1):
            return raw[:match.start(1)]
    return raw


@dataclass(frozen=True)
class Instant:
    """One instant of a script: ``inputs`` maps each present input to its value or ``None``."""

    line: int
    inputs: dict[str, Any] = field(default_factory=dict)
    time_ns: int | None = None


def parse_value(text: str, signal: ir.SignalDecl, loc: SourceLocation) -> Any:
    """A literal value checked against the signal's declared type (the literal grammar and
    wording of :mod:`orccad_app.lang.literals`)."""
    try:
        return read_literal(text, signal.type or "number", signal.name)
    except LiteralError as error:
        raise OrccadError(error.message, loc) from None


def _time(token: str, loc: SourceLocation, previous: int | None) -> int:
    try:
        seconds = float(token[1:])
    except ValueError:
        raise OrccadError(f"'{token}' is not a time: write @T with T in seconds", loc) from None
    if seconds < 0:
        raise OrccadError(f"time {token} is negative", loc)
    if not seconds * 1e9 <= MAX_DURATION_NS:  # NaN and infinities fail this test too
        raise OrccadError(f"time {token} is out of range: T must be a finite number of "
                          f"seconds, at most {MAX_DURATION_NS // 10**9} (one year)", loc)
    time_ns = round(seconds * 1e9)
    if previous is not None and time_ns < previous:
        raise OrccadError(f"time {token} goes backwards (times are absolute and must not "
                          "decrease)", loc)
    return time_ns


def parse_script(text: str, filename: str, inputs: tuple[ir.SignalDecl, ...]) -> list[Instant]:
    """Parse a script against the program's ``inputs``; errors carry file:line:col."""
    by_name = {s.name: s for s in inputs}
    instants: list[Instant] = []
    clock: int | None = None
    for number, raw in enumerate(text.splitlines(), start=1):
        line = _strip_comment(raw)
        if not line.strip() and raw.strip():
            continue  # a comment-only line
        present: dict[str, Any] = {}
        time_ns = None
        pos = 0
        while line[pos:].strip():
            match = _TOKEN.match(line, pos)
            start = match.start(0) + len(match.group(0)) - len(match.group(0).lstrip())
            loc = SourceLocation(filename, number, start + 1)
            at, name, _, value, junk = match.groups()
            pos = match.end()
            if junk is not None:
                raise OrccadError(f"unexpected '{junk}': expected an input signal name", loc)
            if at is not None:
                if present or time_ns is not None:
                    raise OrccadError("the time @T must come first on its line", loc)
                time_ns = clock = _time(at, loc, clock)
                continue
            signal = by_name.get(name)
            if signal is None:
                known = ", ".join(by_name) or "none"
                raise OrccadError(f"'{name}' is not an input signal of this program "
                                  f"(inputs: {known})", loc)
            if value is None and signal.valued:
                raise OrccadError(f"{name} carries a {signal.type}: write {name}(value)", loc)
            if value is not None and not signal.valued:
                raise OrccadError(f"{name} is a pure signal: it takes no value", loc)
            present[name] = None if value is None else parse_value(value, signal, loc)
        instants.append(Instant(number, present, time_ns))
    return instants
