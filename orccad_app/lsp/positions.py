"""Positions: the compiler's 1-based ``line:col`` (in characters) and the protocol's 0-based
``line:character`` (in UTF-16 code units, the LSP default), and file paths and URIs.

No pygls here: plain values, so that each feature module is testable without a server.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from urllib.parse import quote, unquote, urlparse

from orccad_app.diagnostics import SourceLocation

__all__ = ["Span", "TextLines", "path_of_uri", "uri_of_path", "same_file", "word_at"]


@dataclass(frozen=True, slots=True)
class Span:
    """A range in the protocol's terms: 0-based lines, UTF-16 character offsets, end
    exclusive."""

    line: int
    character: int
    end_line: int
    end_character: int


class TextLines:
    """The lines of one text, to convert between the two position systems; ``encoding``
    is the position encoding agreed with the client (``utf-16``, the default, ``utf-8`` or
    ``utf-32``)."""

    def __init__(self, text: str, encoding: str = "utf-16") -> None:
        self.text = text
        self.lines = text.split("\n")
        self.encoding = encoding

    def line(self, number: int) -> str:
        """Line ``number`` (0-based), without its end of line; ``""`` past the end."""
        if 0 <= number < len(self.lines):
            return self.lines[number].rstrip("\r")
        return ""

    def utf16(self, line: int, column: int) -> int:
        """The UTF-16 offset of the 0-based character ``column`` of 0-based ``line``."""
        prefix = self.line(line)[:max(column, 0)]
        return _units(prefix, self.encoding)

    def column(self, line: int, character: int) -> int:
        """The 0-based character index of the UTF-16 offset ``character`` of ``line``."""
        text = self.line(line)
        units = 0
        for index, char in enumerate(text):
            if units >= character:
                return index
            units += _units(char, self.encoding)
        return len(text)

    def offset(self, line: int, character: int) -> int:
        """The index in :attr:`text` of a protocol position."""
        start = sum(len(self.lines[i]) + 1 for i in range(min(line, len(self.lines))))
        return min(start + self.column(line, character), len(self.text))

    def span(self, location: SourceLocation) -> Span:
        """The protocol range of ``location`` (one word when it has no end)."""
        line = max(location.line - 1, 0)
        col = max(location.col - 1, 0)
        if location.end_line is not None and location.end_col is not None \
                and (location.end_line, location.end_col) > (location.line, location.col):
            end_line, end_col = location.end_line - 1, location.end_col - 1
        else:
            end_line, end_col = line, _word_end(self.line(line), col)
        return Span(line, self.utf16(line, col), end_line, self.utf16(end_line, end_col))


def _units(text: str, encoding: str) -> int:
    """The length of ``text`` in the code units of ``encoding``."""
    if encoding == "utf-8":
        return len(text.encode("utf-8", "surrogatepass"))
    if encoding == "utf-32":
        return len(text)
    return len(text.encode("utf-16-le", "surrogatepass")) // 2


def _word_end(text: str, col: int) -> int:
    end = col
    while end < len(text) and (text[end].isalnum() or text[end] == "_"):
        end += 1
    return max(end, min(col + 1, len(text)))


def word_at(text: str, offset: int) -> tuple[str, int]:
    """The identifier around ``offset`` in ``text`` and its start (``("", offset)`` when
    there is none)."""
    start = offset
    while start > 0 and (text[start - 1].isalnum() or text[start - 1] == "_"):
        start -= 1
    end = offset
    while end < len(text) and (text[end].isalnum() or text[end] == "_"):
        end += 1
    return text[start:end], start


def path_of_uri(uri: str) -> str:
    """The file path of a ``file:`` URI (other schemes: the URI's path, as a name)."""
    parsed = urlparse(uri)
    return unquote(parsed.path) if parsed.scheme in ("file", "") else uri


def uri_of_path(path: str) -> str:
    """The ``file:`` URI of ``path`` (made absolute)."""
    return "file://" + quote(os.path.abspath(path))


def same_file(a: str, b: str) -> bool:
    """Whether two paths name the same file (symbolic links and ``..`` resolved)."""
    return os.path.realpath(a) == os.path.realpath(b)
