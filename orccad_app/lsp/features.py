"""The protocol's methods, each a thin handler over its feature module."""

from __future__ import annotations

from lsprotocol import types

from orccad_app.lsp.symbols import document_symbols, folding_ranges

__all__ = ["register"]


def register(server) -> None:
    """Register every feature of ``server`` (an :class:`~.server.OrccadLanguageServer`)."""

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

    @server.feature(types.TEXT_DOCUMENT_DOCUMENT_SYMBOL)
    def symbols(ls, params: types.DocumentSymbolParams) -> list[types.DocumentSymbol]:
        uri = params.text_document.uri
        state = ls.state(uri)
        text = ls.doc_text(uri)
        analysis = state.analysis
        program = analysis.program if analysis is not None and analysis.text == text else None
        return document_symbols(program, ls.doc_lines(uri), state.tokens(text))

    @server.feature(types.TEXT_DOCUMENT_FOLDING_RANGE)
    def folding(ls, params: types.FoldingRangeParams) -> list[types.FoldingRange]:
        uri = params.text_document.uri
        return folding_ranges(ls.state(uri).tokens(ls.doc_text(uri)))
