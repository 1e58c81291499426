"""The error table of a generated automaton: every negative code ``PREFIX_step`` can return.

Each entry is what the Python runtime would report at that point: its kind, its location
(``file:line:col``) and its message, so a C runtime (or the generated ``main``) prints the same
located error as ``orccad react``. Codes are ``-1, -2, …`` in the order entries are made.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass

from orccad_app.diagnostics import NOWHERE, SourceLocation

__all__ = ["ErrorKind", "ErrorEntry", "ErrorTable"]


class ErrorKind(enum.Enum):
    """Where an error comes from."""

    CLOCK = 0
    """The clock went backwards (the caller's fault; no source location)."""
    STATE = 1
    """The memory holds no valid state (not reset, or overwritten)."""
    RELATION = 2
    """The inputs violate a declared ``relation`` (located at the relation)."""
    RUNTIME = 3
    """A run-time error of an expression (located at the expression)."""


@dataclass(frozen=True)
class ErrorEntry:
    """One error code: ``kind``, location and message (without the ``file:line:col``)."""

    kind: ErrorKind
    loc: SourceLocation
    message: str


class ErrorTable:
    """The entries, numbered as made; an identical entry keeps its first code."""

    def __init__(self) -> None:
        self.entries: list[ErrorEntry] = []
        self._codes: dict[tuple, int] = {}
        self.clock = self.code(ErrorKind.CLOCK, NOWHERE, "the clock went backwards")
        self.state = self.code(ErrorKind.STATE, NOWHERE,
                               "the memory holds no valid state (call reset first)")

    def code(self, kind: ErrorKind, loc: SourceLocation, message: str) -> int:
        """The (negative) code of an entry, made on first use."""
        key = (kind, loc.file, loc.line, loc.col, message)
        found = self._codes.get(key)
        if found is None:
            self.entries.append(ErrorEntry(kind, loc, message))
            found = self._codes[key] = -len(self.entries)
        return found
