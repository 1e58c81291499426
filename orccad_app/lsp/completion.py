"""Completion: what may come next at the cursor.

The keywords are the grammar's: lark's interactive parser is fed the text before the cursor
and says which terminals it accepts there (``accepts()``). Where a name may come, the tokens
just before the cursor say which: a law after ``law``, a trajectory after ``trajectory =``,
a Module-Task kind after ``module x :``, an observer after ``from`` or ``measure``, a robot
type after ``robot x :``, a Robot-Task after ``run``, a mission after ``run mission``, an
exception after ``catch``, a protocol after ``connect a.b -> c.d :``; otherwise the signals,
variables and tasks in scope. Registry names and Robot-Tasks come as snippets with their
parameters and defaults. When the text before the cursor does not parse, every keyword and
every name in scope is offered.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from lark.exceptions import UnexpectedInput
from lsprotocol import types

from orccad_app.diagnostics import value_text
from orccad_app.lang import ast
from orccad_app.lang.ast_robottask import PROTOCOLS
from orccad_app.lang.parser import keywords, literal_terminals, parse_interactive
from orccad_app.lang.walk import nodes
from orccad_app.lsp.hover import expr_text
from orccad_app.lsp.tokens import Tok, tokens

__all__ = ["Context", "context_at", "completions"]

CK = types.CompletionItemKind


@dataclass(frozen=True)
class Context:
    """Where the cursor is: the terminals the grammar accepts there (``None`` when the text
    before it does not parse), the enclosing top-level declaration (``mission``/
    ``robottask`` and its name, or ``None``) and the tokens before the cursor."""

    accepts: frozenset[str] | None
    item: tuple[str, str] | None
    before: list[Tok]


def _accepts(text: str) -> frozenset[str] | None:
    try:
        parser = parse_interactive(text)
        parser.exhaust_lexer()
        return frozenset(parser.accepts())
    except UnexpectedInput:
        return None
    except RecursionError:
        return None


def _enclosing(toks: list[Tok]) -> tuple[str, str] | None:
    depth, current = 0, None
    for index, tok in enumerate(toks):
        if tok.kind == "LBRACE":
            depth += 1
        elif tok.kind == "RBRACE":
            depth = max(depth - 1, 0)
            if depth == 0:
                current = None
        elif depth == 0 and tok.kind in ("MISSION", "ROBOTTASK") and index + 1 < len(toks) \
                and toks[index + 1].kind == "NAME":
            current = (tok.kind.lower(), toks[index + 1].text)
    return current


def context_at(text: str, offset: int) -> tuple[Context, str]:
    """The context of the cursor at ``offset`` in ``text``, and the part of a name typed
    before it."""
    start = offset
    while start > 0 and (text[start - 1].isalnum() or text[start - 1] == "_"):
        start -= 1
    before = text[:start]
    toks = tokens(before)
    return Context(_accepts(before), _enclosing(toks), toks), text[start:offset]


def _snippet(name: str, params: tuple, snippets: bool) -> tuple[str, types.InsertTextFormat]:
    if not snippets:
        return name, types.InsertTextFormat.PlainText
    parts = []
    for number, (pname, default) in enumerate(params, 1):
        shown = pname if default is None else default if isinstance(default, str) \
            else _value(default)
        shown = shown.replace("$", "\\$").replace("}", "\\}")
        parts.append(f"{pname} = ${{{number}:{shown}}}")
    return f"{name}({', '.join(parts)})", types.InsertTextFormat.Snippet


def _value(value: Any) -> str:
    """A default as the language writes it, a real keeping its point (``400.0``: an
    integer literal would not be a real)."""
    if isinstance(value, float) and value.is_integer():
        return f"{value:.1f}"
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_value(v) for v in value) + "]"
    return value_text(value)


def _registry_items(host: Any, attributes: tuple[str, ...], what: str,
                    snippets: bool) -> list[types.CompletionItem]:
    items: list[types.CompletionItem] = []
    if host is None:
        return items
    for attribute in attributes:
        registry = getattr(host, attribute)
        for name in registry.names():
            entry = registry.get(name)
            params = tuple((p.name, None if getattr(p, "required", False) else p.default)
                           for p in (getattr(entry, "params", ()) or ()))
            text, fmt = _snippet(name, params, snippets)
            items.append(types.CompletionItem(
                label=name, kind=CK.Function, detail=what,
                documentation=getattr(entry, "summary", None),
                insert_text=text, insert_text_format=fmt))
    return items


def _task_items(program: ast.Program | None, snippets: bool) -> list[types.CompletionItem]:
    if program is None:
        return []
    items = []
    for task in program.robottasks:
        params = tuple((p.name, None if p.default is None else expr_text(p.default))
                       for p in task.params)
        text, fmt = _snippet(task.name, params, snippets)
        items.append(types.CompletionItem(label=task.name, kind=CK.Class,
                                          detail=f"robottask on {task.robot}",
                                          insert_text=text, insert_text_format=fmt))
    return items


def _names(kind: types.CompletionItemKind, names, detail: str) -> list[types.CompletionItem]:
    return [types.CompletionItem(label=n, kind=kind, detail=detail)
            for n in dict.fromkeys(names)]


def _scope_items(program: ast.Program | None,
                 item: tuple[str, str] | None) -> list[types.CompletionItem]:
    """Signals, variables and tasks visible in ``item`` (file-level names elsewhere)."""
    if program is None:
        return []
    out = _names(CK.Event, (s.name for s in program.signals), "signal (file level)")
    if item is not None and item[0] == "mission":
        mission = program.mission(item[1])
        if mission is not None:
            out += _names(CK.Event, (s.name for s in mission.signature + mission.signals),
                          f"signal of {mission.name}")
            for node in nodes(mission.body):
                if isinstance(node, ast.LocalSignals):
                    out += _names(CK.Event, (s.name for s in node.signals), "local signal")
                elif isinstance(node, ast.VarDecl):
                    out += _names(CK.Variable, [node.name], "variable")
    if item is not None and item[0] == "robottask":
        task = program.robottask(item[1])
        if task is not None:
            out += _names(CK.Module, (m.name for m in task.modules), "Module-Task")
            out += _names(CK.TypeParameter, (p.name for p in task.params), "parameter")
    out += _names(CK.Struct, (r.name for r in program.robots), "robot")
    out += _names(CK.Class, (t.name for t in program.robottasks), "robottask")
    out += _names(CK.Function, (m.name for m in program.missions + program.imported_missions),
                  "mission")
    return out


def _exceptions(program: ast.Program | None) -> list[types.CompletionItem]:
    names = ["Timeout"]
    if program is not None:
        for task in program.robottasks:
            names += [e.name for e in task.exceptions] + list(task.raisable())
    return _names(CK.EnumMember, names, "exception")


def _in_catch(toks: list[Tok]) -> bool:
    for tok in reversed(toks):
        if tok.kind == "CATCH":
            return True
        if tok.kind not in ("COMMA", "NAME"):
            return False
    return False


def _name_items(context: Context, program: ast.Program | None, host: Any,
                snippets: bool) -> list[types.CompletionItem]:
    toks = context.before
    last = toks[-1] if toks else None
    kind = last.kind if last is not None else None
    two = toks[-2] if len(toks) >= 2 else None
    three = toks[-3] if len(toks) >= 3 else None
    if kind == "LAW":
        return _registry_items(host, ("control_laws",), "control law", snippets)
    if kind == "TASK_FUNCTION":
        return _registry_items(host, ("task_functions",), "task function", snippets)
    if kind == "EQUAL" and two is not None and two.text == "trajectory":
        return _registry_items(host, ("trajectories",), "trajectory", snippets)
    if kind == "COLON" and three is not None and three.kind == "MODULE":
        return _registry_items(host, ("module_kinds", "observers"), "module kind", snippets)
    if kind == "COLON" and three is not None and three.kind == "ROBOT":
        return _registry_items(host, ("robot_types",), "robot type", snippets)
    if kind == "MEASURE":
        return _registry_items(host, ("observers",), "observer", snippets)
    if kind == "FROM" and context.item is not None and context.item[0] == "robottask":
        task = program.robottask(context.item[1]) if program is not None else None
        modules = _names(CK.Module, (m.name for m in task.modules) if task else (),
                         "Module-Task")
        return modules + _registry_items(host, ("observers",), "observer", snippets)
    if kind == "MISSION" and two is not None and two.kind == "RUN":
        names = (m.name for m in program.missions + program.imported_missions) \
            if program is not None else ()
        return _names(CK.Function, names, "mission")
    if kind == "RUN":
        return _task_items(program, snippets)
    if kind == "ON" and context.item is None:
        return _names(CK.Struct, (r.name for r in program.robots) if program else (), "robot")
    if _in_catch(toks):
        return _exceptions(program)
    return _scope_items(program, context.item)


def completions(text: str, offset: int, program: ast.Program | None, host: Any,
                snippets: bool = True) -> list[types.CompletionItem]:
    """The completion items at ``offset`` of ``text``; ``program`` is the document's last
    parsed AST (for the names in scope), ``host`` the plugin host (for registry names)."""
    context, _typed = context_at(text, offset)
    literals = literal_terminals()
    words = keywords()
    if context.accepts is None:
        items = _names(CK.Keyword, sorted(words), "keyword")
        return items + _scope_items(program, context.item)
    items = _names(CK.Keyword, sorted(literals[t] for t in context.accepts
                                      if t in literals and literals[t] in words), "keyword")
    if "PROTOCOL" in context.accepts:
        items += _names(CK.EnumMember, PROTOCOLS, "port protocol")
    if "NAME" in context.accepts:
        items += _name_items(context, program, host, snippets)
    return items
