"""The protocol's methods, each a thin handler over its feature module."""

from __future__ import annotations

import json
from typing import Any

from lsprotocol import types
from pygls.exceptions import JsonRpcInvalidParams

from orccad_app.lsp.analysis import refusal
from orccad_app.lsp.completion import completions
from orccad_app.lsp.hover import hover_declaration, hover_registry
from orccad_app.lsp.index import token_at
from orccad_app.lsp.navigation import declaration_at, definition, references
from orccad_app.lsp.symbols import document_symbols, folding_ranges

__all__ = ["register", "CHECK_COMMAND", "command_uri"]

#: The command that proves the properties of a document (argument: its URI).
CHECK_COMMAND = "orccad.check"


def register(server) -> None:
    """Register every feature of ``server`` (an :class:`~.server.OrccadLanguageServer`)."""
    _sync(server)
    _outline(server)
    _navigation(server)
    _completion(server)
    _proof(server)


def _sync(server) -> None:
    @server.feature(types.TEXT_DOCUMENT_DID_OPEN)
    def did_open(ls, params: types.DidOpenTextDocumentParams) -> None:
        ls.schedule(params.text_document.uri, 0.0)
        ls.schedule_dependents(params.text_document.uri)

    @server.feature(types.TEXT_DOCUMENT_DID_CHANGE)
    def did_change(ls, params: types.DidChangeTextDocumentParams) -> None:
        uri = params.text_document.uri
        ls.changed(uri)
        ls.schedule(uri)
        ls.schedule_dependents(uri)

    @server.feature(types.TEXT_DOCUMENT_DID_CLOSE)
    def did_close(ls, params: types.DidCloseTextDocumentParams) -> None:
        ls.close(params.text_document.uri)

    @server.feature(types.SHUTDOWN)
    def shutdown(ls, params) -> None:
        ls.proofs.cancel_all()


def _outline(server) -> None:
    @server.feature(types.TEXT_DOCUMENT_DOCUMENT_SYMBOL)
    def symbols(ls, params: types.DocumentSymbolParams) -> list[types.DocumentSymbol]:
        uri = params.text_document.uri
        text = ls.doc_text(uri)
        analysis = ls.state(uri).analysis
        program = analysis.program if analysis is not None and analysis.text == text else None
        return document_symbols(program, ls.doc_lines(uri), ls.state(uri).tokens(text))

    @server.feature(types.TEXT_DOCUMENT_FOLDING_RANGE)
    def folding(ls, params: types.FoldingRangeParams) -> list[types.FoldingRange]:
        uri = params.text_document.uri
        return folding_ranges(ls.state(uri).tokens(ls.doc_text(uri)))


def _where(ls, uri: str, position: types.Position):
    """The document's tokens, index, lines, and the cursor as a character column."""
    text = ls.doc_text(uri)
    state = ls.state(uri)
    lines = ls.doc_lines(uri)
    return state.tokens(text), state.index(), lines, lines.column(position.line,
                                                                  position.character)


def _navigation(server) -> None:
    @server.feature(types.TEXT_DOCUMENT_HOVER)
    def hover(ls, params: types.HoverParams) -> types.Hover | None:
        uri = params.text_document.uri
        if refusal(ls.doc_text(uri)) is not None:
            return None
        toks, index, lines, col = _where(ls, uri, params.position)
        at = token_at(toks, params.position.line, col)
        if at is None or toks[at].kind != "NAME":
            return None
        tok = toks[at]
        text = None
        if index is not None:
            found = declaration_at(index, toks, params.position.line, col)
            if found is not None:
                analysis = ls.state(uri).parsed
                text = hover_declaration(found[0], index.program,
                                         analysis.source if analysis else None,
                                         ls.verdict_text(uri))
        if text is None:
            text = hover_registry(tok.text, ls.host())
        if text is None:
            return None
        return types.Hover(
            contents=types.MarkupContent(kind=types.MarkupKind.Markdown, value=text),
            range=types.Range(types.Position(tok.line, lines.utf16(tok.line, tok.col)),
                              types.Position(tok.end_line,
                                             lines.utf16(tok.end_line, tok.end_col))))

    @server.feature(types.TEXT_DOCUMENT_DEFINITION)
    def goto_definition(ls, params: types.DefinitionParams) -> types.Location | None:
        uri = params.text_document.uri
        toks, index, lines, col = _where(ls, uri, params.position)
        if index is None:
            return None
        return definition(index, toks, ls.state(uri).path, lines, params.position.line, col,
                          ls.file_text)

    @server.feature(types.TEXT_DOCUMENT_REFERENCES)
    def find_references(ls, params: types.ReferenceParams) -> list[types.Location]:
        uri = params.text_document.uri
        toks, index, lines, col = _where(ls, uri, params.position)
        if index is None:
            return []
        return references(index, toks, ls.state(uri).path, lines, params.position.line, col,
                          params.context.include_declaration, ls.file_text)


def _completion(server) -> None:
    @server.feature(types.TEXT_DOCUMENT_COMPLETION,
                    types.CompletionOptions(trigger_characters=[" ", ":", "="]))
    def complete(ls, params: types.CompletionParams) -> types.CompletionList:
        uri = params.text_document.uri
        text = ls.doc_text(uri)
        if refusal(text) is not None:  # too large or binary: no work at all
            return types.CompletionList(is_incomplete=False, items=[])
        lines = ls.doc_lines(uri)
        offset = lines.offset(params.position.line, params.position.character)
        parsed = ls.state(uri).parsed
        items = completions(text, offset, parsed.program if parsed else None, ls.host(),
                            ls.snippets())
        return types.CompletionList(is_incomplete=False, items=items)


def _proof(server) -> None:
    @server.feature(types.TEXT_DOCUMENT_DID_SAVE)
    def did_save(ls, params: types.DidSaveTextDocumentParams) -> None:
        ls.prove(params.text_document.uri)

    @server.command(CHECK_COMMAND)
    def check(ls, *arguments) -> str:
        uri = command_uri(arguments)
        if uri is None:
            raise JsonRpcInvalidParams(f"{CHECK_COMMAND}: expected the URI of an open document "
                                       f"([uri], [{{\"uri\": uri}}] or [[uri]]), got "
                                       f"{_shown(list(arguments))}")
        if not ls.opened(uri):
            raise JsonRpcInvalidParams(f"{CHECK_COMMAND}: {uri} is not an open document")
        return ls.prove(uri)


def command_uri(arguments: tuple[Any, ...]) -> str | None:
    """The document of ``orccad.check``'s arguments, as clients send it: ``[uri]`` (the VS
    Code extension), ``[{"uri": uri}]`` (a ``TextDocumentIdentifier``) or ``[[uri]]`` (a
    client that passes its arguments as one list); ``None`` for anything else."""
    value = arguments[0] if len(arguments) == 1 else None
    if isinstance(value, list) and len(value) == 1:
        value = value[0]
    if isinstance(value, dict):
        value = value.get("uri")
    return value if isinstance(value, str) and value else None


def _shown(value: Any) -> str:
    text = json.dumps(value, default=str)
    return text if len(text) <= 120 else text[:117] + "..."
