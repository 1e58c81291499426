"""Outline (document symbols) and folding ranges.

From the AST when the document parses: robots, signals, Robot-Tasks (with their parameters,
Module-Tasks and exceptions), missions (with their signals and ``run`` sites), properties,
imports. From the grammar's tokens when it does not: every top-level declaration keyword
followed by its name, up to its closing brace or semicolon. Folding ranges are the brace
pairs spanning lines, from the tokens either way.
"""

from __future__ import annotations

import re

from lsprotocol import types

from orccad_app.diagnostics import SourceLocation
from orccad_app.lang import ast
from orccad_app.lang.walk import nodes
from orccad_app.lsp.positions import TextLines
from orccad_app.lsp.problems import to_range
from orccad_app.lsp.tokens import Tok, brace_pairs

__all__ = ["document_symbols", "folding_ranges"]

K = types.SymbolKind


def document_symbols(program: ast.Program | None, lines: TextLines,
                     toks: list[Tok]) -> list[types.DocumentSymbol]:
    """The outline of a document (its text in ``lines``): from ``program`` if it parsed,
    else from ``toks``."""
    if program is None:
        return _from_tokens(toks, lines)
    out: list[types.DocumentSymbol] = []
    for item in program.items:
        symbol = _item(item, lines)
        if symbol is not None:
            out.append(symbol)
    return out


def _symbol(name: str, kind: types.SymbolKind, loc: SourceLocation, lines: TextLines,
            detail: str | None = None,
            children: list[types.DocumentSymbol] | None = None) -> types.DocumentSymbol:
    whole = to_range(loc, lines)
    return types.DocumentSymbol(name=name or "?", kind=kind, range=whole,
                                selection_range=_name_range(name, loc, lines, whole),
                                detail=detail, children=children or None)


def _name_range(name: str, loc: SourceLocation, lines: TextLines,
                whole: types.Range) -> types.Range:
    """Where ``name`` is written on the first line of ``loc`` (the whole start otherwise)."""
    line = max(loc.line - 1, 0)
    text = lines.line(line)
    bare = name.split(".")[-1]
    match = re.compile(rf"\b{re.escape(bare)}\b").search(text, max(loc.col - 1, 0))
    if match is None or not bare:
        return types.Range(whole.start, whole.start)
    return types.Range(types.Position(line, lines.utf16(line, match.start())),
                       types.Position(line, lines.utf16(line, match.end())))


def _item(item, lines: TextLines) -> types.DocumentSymbol | None:
    if isinstance(item, ast.Robot):
        return _symbol(item.name, K.Object, item.loc, lines, f"robot : {item.type}")
    if isinstance(item, ast.SignalDecl):
        return _signal(item, lines)
    if isinstance(item, ast.RobotTask):
        return _robottask(item, lines)
    if isinstance(item, ast.Mission):
        return _mission(item, lines)
    if isinstance(item, (ast.Property, ast.Assumption)):
        kind = "property" if isinstance(item, ast.Property) else "assume"
        name = f"{item.mission}.{item.name}" if item.mission else item.name
        return _symbol(name, K.Boolean, item.loc, lines, kind)
    if isinstance(item, ast.Import):
        children = [_symbol(n.name, K.Function, n.loc, lines, "imported mission")
                    for n in item.names]
        return _symbol(item.path, K.Package, item.loc, lines, "import", children)
    return None


def _signal(decl: ast.SignalDecl, lines: TextLines) -> types.DocumentSymbol:
    detail = decl.direction.value + (f" : {decl.type}" if decl.type else "")
    return _symbol(decl.name, K.Event, decl.loc, lines, detail)


def _robottask(task: ast.RobotTask, lines: TextLines) -> types.DocumentSymbol:
    children = [_symbol(p.name, K.TypeParameter, p.loc, lines, p.type) for p in task.params]
    children += [_symbol(m.name, K.Module, m.loc, lines, f"module : {m.kind}")
                 for m in task.modules]
    children += [_symbol(e.name, K.EnumMember, e.loc, lines,
                         f"exception, type {e.type.number} ({e.type.value})")
                 for e in task.exceptions]
    return _symbol(task.name, K.Class, task.loc, lines, f"robottask on {task.robot}", children)


def _mission(mission: ast.Mission, lines: TextLines) -> types.DocumentSymbol:
    children = [_signal(s, lines) for s in mission.signature + mission.signals]
    for node in nodes(mission.body):
        if isinstance(node, ast.Run):
            children.append(_symbol(node.task, K.Method, node.loc, lines, "run"))
        elif isinstance(node, ast.RunMission):
            children.append(_symbol(node.mission, K.Function, node.loc, lines, "run mission"))
        elif isinstance(node, ast.VarDecl):
            children.append(_symbol(node.name, K.Variable, node.loc, lines, "var"))
        elif isinstance(node, ast.LocalSignals):
            children += [_signal(s, lines) for s in node.signals]
    return _symbol(mission.name, K.Function, mission.loc, lines, "mission", children)


#: Declaration keywords read from the tokens of a document that does not parse.
_DECLARATIONS = {"MISSION": K.Function, "ROBOTTASK": K.Class, "ROBOT": K.Object,
                 "PROPERTY": K.Boolean, "INPUT": K.Event, "OUTPUT": K.Event}


def _from_tokens(toks: list[Tok], lines: TextLines) -> list[types.DocumentSymbol]:
    out: list[types.DocumentSymbol] = []
    depth = 0
    index = 0
    while index < len(toks):
        tok = toks[index]
        if tok.kind == "LBRACE":
            depth += 1
        elif tok.kind == "RBRACE":
            depth = max(depth - 1, 0)
        elif depth == 0 and tok.kind in _DECLARATIONS and index + 1 < len(toks) \
                and toks[index + 1].kind == "NAME":
            name = toks[index + 1]
            if tok.kind == "PROPERTY" and index + 3 < len(toks) \
                    and toks[index + 2].kind == "DOT":
                label = f"{name.text}.{toks[index + 3].text}"
            else:
                label = name.text
            end = _declaration_end(toks, index, tok.kind in ("MISSION", "ROBOTTASK"))
            whole = SourceLocation("", tok.line + 1, tok.col + 1, end.end_line + 1,
                                   end.end_col + 1)
            out.append(_symbol(label, _DECLARATIONS[tok.kind], whole, lines,
                               tok.text.lower()))
        index += 1
    return out


def _declaration_end(toks: list[Tok], index: int, block: bool) -> Tok:
    """The token that ends the declaration starting at ``toks[index]``: its closing brace
    (or the last token when unclosed) for a block, else its semicolon."""
    depth = 0
    for tok in toks[index:]:
        if block and tok.kind == "LBRACE":
            depth += 1
        elif block and tok.kind == "RBRACE":
            depth -= 1
            if depth == 0:
                return tok
        elif not block and tok.kind == "SEMICOLON":
            return tok
        elif not block and tok.kind in _DECLARATIONS and tok is not toks[index]:
            break
    return toks[-1] if block else toks[min(index + 1, len(toks) - 1)]


def folding_ranges(toks: list[Tok]) -> list[types.FoldingRange]:
    """One folding range per brace pair spanning several lines (the closing line kept)."""
    out = []
    for opening, closing in brace_pairs(toks):
        end = closing.line - 1 if closing is not None else (toks[-1].line if toks else 0)
        if end > opening.line:
            out.append(types.FoldingRange(start_line=opening.line, end_line=end,
                                          kind=types.FoldingRangeKind.Region))
    return out
