"""Go to definition and find references: robottasks, missions (sub-missions and imported
ones, in their own file), signals, variables, robots, parameters, Module-Tasks, exceptions,
traps and properties, resolved by :class:`~.index.Index`."""

from __future__ import annotations

import re
from typing import Callable

from lsprotocol import types

from orccad_app.lsp.index import Declaration, Index, token_at
from orccad_app.lsp.positions import TextLines, same_file, uri_of_path
from orccad_app.lsp.tokens import Tok

__all__ = ["declaration_at", "name_location", "definition", "references"]

TextOf = Callable[[str], "str | None"]


def declaration_at(index: Index, toks: list[Tok], line: int,
                   col: int) -> tuple[Declaration, Tok] | None:
    """The declaration named under the 0-based ``line:col`` (a character column), with the
    token there."""
    at = token_at(toks, line, col)
    if at is None:
        return None
    decl = index.resolve(toks, at)
    return None if decl is None else (decl, toks[at])


def name_location(decl: Declaration, path: str, lines: TextLines,
                  text_of: TextOf) -> types.Location:
    """Where ``decl``'s name is written (in its own file, maybe not the document ``path``
    whose text is ``lines``)."""
    loc = decl.loc
    file_lines = lines if same_file(loc.file, path) else None
    if file_lines is None:
        other = text_of(loc.file)
        file_lines = TextLines(other or "", lines.encoding)
    pattern = re.compile(rf"\b{re.escape(decl.name)}\b")
    for number in range(max(loc.line - 1, 0), min((loc.end_line or loc.line) + 1,
                                                   len(file_lines.lines))):
        start = max(loc.col - 1, 0) if number == loc.line - 1 else 0
        match = pattern.search(file_lines.line(number), start)
        if match is not None:
            return types.Location(uri_of_path(loc.file), types.Range(
                types.Position(number, file_lines.utf16(number, match.start())),
                types.Position(number, file_lines.utf16(number, match.end()))))
    line = max(loc.line - 1, 0)
    at = types.Position(line, file_lines.utf16(line, max(loc.col - 1, 0)))
    return types.Location(uri_of_path(loc.file), types.Range(at, at))


def definition(index: Index, toks: list[Tok], path: str, lines: TextLines, line: int,
               col: int, text_of: TextOf) -> types.Location | None:
    """The location of the declaration of the name under ``line:col``."""
    found = declaration_at(index, toks, line, col)
    if found is None:
        return None
    return name_location(found[0], path, lines, text_of)


def references(index: Index, toks: list[Tok], path: str, lines: TextLines, line: int,
               col: int, include_declaration: bool,
               text_of: TextOf) -> list[types.Location]:
    """Every use in the document of the name under ``line:col`` (and its declaration, when
    asked), in source order."""
    found = declaration_at(index, toks, line, col)
    if found is None:
        return []
    decl = found[0]
    uri = uri_of_path(path)
    out = [types.Location(uri, _range(toks[i], lines)) for i in index.references(toks, decl)]
    declared = name_location(decl, path, lines, text_of)
    out = [loc for loc in out if loc != declared]
    if include_declaration:
        out.insert(0, declared)
    return out


def _range(tok: Tok, lines: TextLines) -> types.Range:
    return types.Range(types.Position(tok.line, lines.utf16(tok.line, tok.col)),
                       types.Position(tok.end_line, lines.utf16(tok.end_line, tok.end_col)))
