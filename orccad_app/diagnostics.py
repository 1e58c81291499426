"""Source locations and located errors shared by every layer.

Every user-facing error in ORCCAD is an :class:`OrccadError`. When it carries a
:class:`SourceLocation`, :func:`format_diagnostic` renders it the way compilers do::

    missions/abro.orc:7:9: error: undeclared signal 'C'
        await C;
              ^

The CLI prints that and exits with status 2; no Python traceback reaches the user.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Mapping

__all__ = [
    "value_text",
    "value_excerpt",
    "cut",
    "arguments_text",
    "SourceLocation",
    "OrccadError",
    "Diagnostic",
    "format_diagnostic",
    "NOWHERE",
]


@dataclass(frozen=True, slots=True)
class SourceLocation:
    """A position in a source file; ``line`` and ``col`` are 1-based."""

    file: str
    line: int
    col: int
    end_line: int | None = None
    end_col: int | None = None

    def __str__(self) -> str:
        return f"{self.file}:{self.line}:{self.col}"


NOWHERE = SourceLocation("<unknown>", 0, 0)


@dataclass(frozen=True, slots=True)
class Diagnostic:
    """One message about the source: ``severity`` is ``error``, ``warning`` or ``note``."""

    severity: str
    message: str
    location: SourceLocation | None = None

    def format(self, source: str | None = None) -> str:
        return format_diagnostic(self.severity, self.message, self.location, source)


class OrccadError(Exception):
    """A user-facing error: bad input, never a bug. ``exit_status`` is 2 unless set."""

    exit_status = 2

    def __init__(self, message: str, location: SourceLocation | None = None,
                 notes: tuple[Diagnostic, ...] = ()):
        super().__init__(message)
        self.message = message
        self.location = location
        self.notes = notes

    def format(self, source: str | None = None) -> str:
        text = format_diagnostic("error", self.message, self.location, source)
        for note in self.notes:
            text += "\n" + note.format(source)
        return text


def format_diagnostic(severity: str, message: str, location: SourceLocation | None,
                      source: str | None = None) -> str:
    """Render ``file:line:col: severity: message`` plus the source line and a caret.

    Lines are counted at ``\\n`` only (as the parser counts them: a form feed or U+2028 does
    not start a line); tabs are expanded to 4 columns in the shown line and under it, so the
    caret stays under the character it points at.
    """
    if location is None or location.line <= 0:
        return f"orccad: {severity}: {message}"
    head = f"{location}: {severity}: {message}"
    if source is None:
        source = _read(location.file)
        if source is None:
            return head
    lines = source.split("\n")
    if location.line > len(lines):
        return head
    line = lines[location.line - 1].rstrip("\r")
    start = max(location.col - 1, 0)
    end = start + 1
    if location.end_line == location.line and location.end_col and location.end_col > location.col:
        end = location.end_col - 1
    if len(line) > _SHOWN_WIDTH:  # a very long line: show a window around the column
        first = max(0, min(start - _SHOWN_WIDTH // 3, len(line) - _SHOWN_WIDTH))
        line, start, end = line[first:first + _SHOWN_WIDTH], start - first, end - first
        end = min(end, len(line))
    text = _shown(line)
    before = len(_shown(line[:start]))
    width = max(len(_shown(line[:end])) - before, 1)
    caret = " " * before + "^" + "~" * (width - 1)
    return f"{head}\n    {text}\n    {caret}"


#: Widest excerpt of a source line shown under a diagnostic [characters].
_SHOWN_WIDTH = 160


def _shown(text: str) -> str:
    """``text`` as printed under a diagnostic: tabs expanded, other control characters (form
    feed, U+2028, ...) shown as one space each so that columns stay aligned."""
    return "".join(c if c.isprintable() or c == "\t" else " " for c in text).expandtabs(4)


def _read(path: str) -> str | None:
    """The text of ``path`` for a diagnostic (undecodable bytes replaced), or None."""
    try:
        with open(path, "rb") as handle:
            data = handle.read(2_000_000)
    except OSError:
        return None
    if data.startswith(b"\xef\xbb\xbf"):
        data = data[3:]
    return data.decode("utf-8", "replace")


def value_text(value: Any) -> str:
    """A value as the language writes it (``[10, 0, 15]``, ``2.5``, ``true``, ``"text"``)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return f"{value:g}" if math.isfinite(value) else str(value)
    if isinstance(value, str):
        return '"' + value.replace('"', '\\"') + '"'
    if isinstance(value, (list, tuple)) or hasattr(value, "tolist"):
        items = value.tolist() if hasattr(value, "tolist") else list(value)
        if isinstance(items, list):
            return "[" + ", ".join(value_text(v) for v in items) + "]"
        return value_text(items)
    return str(value)


#: Most characters of a user's text echoed in a message (:func:`cut`).
MESSAGE_EXCERPT_CHARS = 160
#: Most components of a vector shown in a message (:func:`value_excerpt`).
MESSAGE_EXCERPT_COMPONENTS = 8


def cut(text: str, limit: int = MESSAGE_EXCERPT_CHARS) -> str:
    """``text`` itself, or its start and its end around ``…`` with its length when it is
    longer than ``limit`` characters: a message echoes what the user wrote, never half a
    megabyte of it."""
    if len(text) <= limit:
        return text
    keep = max(1, (limit - 30) // 2)
    return f"{text[:keep]} … {text[-keep:]} ({len(text)} characters)"


def value_excerpt(value: Any) -> str:
    """:func:`value_text` for a message: a vector of more than
    :data:`MESSAGE_EXCERPT_COMPONENTS` components shows its first and last ones and its size
    (``[1, 2, 3, 4, …, 9, 10] (10 components)``), a long string is :func:`cut`."""
    if isinstance(value, (list, tuple)) or hasattr(value, "tolist"):
        items = value.tolist() if hasattr(value, "tolist") else list(value)
        if isinstance(items, list) and len(items) > MESSAGE_EXCERPT_COMPONENTS:
            half = MESSAGE_EXCERPT_COMPONENTS // 2
            shown = [value_excerpt(v) for v in (*items[:half], *items[-half:])]
            return (f"[{', '.join(shown[:half])}, …, {', '.join(shown[half:])}] "
                    f"({len(items)} components)")
        if isinstance(items, list):
            return "[" + ", ".join(value_excerpt(v) for v in items) + "]"
    return cut(value_text(value))


def arguments_text(arguments: Mapping[str, Any]) -> str:
    """``target=[10, 0, 15], speed=1.5``."""
    return ", ".join(f"{name}={value_text(value)}" for name, value in arguments.items())
