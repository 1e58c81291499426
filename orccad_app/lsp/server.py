"""``orccad lsp``: the language server (pygls), over stdio.

Documents are analysed by the compiler pipeline on open and on change, after a short debounce
(:data:`DEBOUNCE_S`; a burst of keystrokes is analysed once, at its end), one analysis at a
time on a worker thread so that requests are answered meanwhile; a result for a version the
editor has since changed is dropped. The features live in their own modules (:mod:`.symbols`,
:mod:`.hover`, :mod:`.navigation`, :mod:`.completion`, :mod:`.proof`); this module keeps the
documents and wires the protocol to them.

The server never exits on bad input: an unexpected exception while analysing is one
diagnostic (an internal error, to report), and the server goes on.
"""

from __future__ import annotations

import asyncio
import logging
import os
import threading
from concurrent.futures import ThreadPoolExecutor
from typing import Any
from urllib.parse import unquote

from lsprotocol import types
from pygls.exceptions import FeatureRequestError, JsonRpcInvalidParams
from pygls.lsp.server import LanguageServer

from orccad_app import __version__
from orccad_app.diagnostics import SourceLocation
from orccad_app.lsp.analysis import Analysis, Problem, Severity, analyze
from orccad_app.lsp.documents import DocumentState, buffer_reader, depends_on, text_of
from orccad_app.lsp.positions import TextLines, path_of_uri, same_file
from orccad_app.lsp.problems import SOURCE, diagnostics_by_uri, to_range
from orccad_app.lsp.proof import ProofRunner, Verdict, verdict_diagnostics, verdicts_of

__all__ = ["OrccadLanguageServer", "DEBOUNCE_S", "serve"]

#: Wait after a change before analysing [s]: a burst of changes is analysed once.
DEBOUNCE_S = 0.03

logger = logging.getLogger(__name__)


class OrccadLanguageServer(LanguageServer):
    """The plan language's server: documents, their analyses, the plugin host."""

    def __init__(self, debounce_s: float = DEBOUNCE_S, proof_budget_s: float = 60.0) -> None:
        super().__init__("orccad", __version__,
                         text_document_sync_kind=types.TextDocumentSyncKind.Incremental)
        self.debounce_s = debounce_s
        self.proof_budget_s = proof_budget_s
        self.states: dict[str, DocumentState] = {}
        self.pending: dict[str, asyncio.Task] = {}
        self.foreign: dict[str, set[str]] = {}
        self.extra: dict[str, list[types.Diagnostic]] = {}  # e.g. the proof's verdicts
        self.executor = ThreadPoolExecutor(1, thread_name_prefix="orccad-analysis")
        self._host: Any = None
        self._host_problems: tuple[Problem, ...] = ()
        self._host_loaded = False
        self._host_lock = threading.Lock()
        self.proofs = ProofRunner(proof_budget_s)
        self.verdicts: dict[str, dict[tuple[str | None, str], Verdict]] = {}

    def report_server_error(self, error: Exception, source) -> None:
        """A handler's failure: one line in the log, never a pop-up in the editor (a
        request's failure is its error response already; a notification's, such as a
        change to a document never opened, is the editor's to fix)."""
        if source is not FeatureRequestError:  # a request's: pygls has said it already
            logger.warning("%s: %s", type(error).__name__, error)

    # -- documents ---------------------------------------------------------------------

    @property
    def encoding(self) -> str:
        """The position encoding agreed with the client (``utf-16`` unless it chose)."""
        try:
            return str(self.workspace.position_encoding or "utf-16")
        except RuntimeError:  # before initialize
            return "utf-16"

    def state(self, uri: str) -> DocumentState:
        """The server's record of the document ``uri`` (made on first use)."""
        if uri not in self.states:
            self.states[uri] = DocumentState(uri, path_of_uri(uri))
        return self.states[uri]

    def doc_text(self, uri: str) -> str:
        """The editor's current text of ``uri``; a document the editor did not open is
        refused (invalid params): the disk is never read for it (it may be a FIFO, or
        ``/dev/zero``)."""
        if not self.opened(uri):
            raise JsonRpcInvalidParams(f"{uri}: not an open document (textDocument/didOpen "
                                       "first)")
        return self.workspace.get_text_document(uri).source

    def opened(self, uri: str) -> bool:
        """Whether the editor has ``uri`` open (pygls keys its documents unescaped:
        ``file:///a%20b.orc`` is open as ``file:///a b.orc``)."""
        return unquote(uri) in self.workspace.text_documents

    def doc_version(self, uri: str) -> int | None:
        return self.workspace.get_text_document(uri).version

    def doc_lines(self, uri: str) -> TextLines:
        return TextLines(self.doc_text(uri), self.encoding)

    def file_text(self, path: str) -> str | None:
        """The text of any file: its open buffer, else the disk (``None`` if unreadable)."""
        return text_of(self.buffers())(path)

    def snippets(self) -> bool:
        """Whether the client takes completion snippets."""
        try:
            item: Any = self.client_capabilities.text_document
            item = item.completion.completion_item
            return bool(item.snippet_support)
        except AttributeError:
            return False

    def buffers(self) -> dict[str, str]:
        """Real path → unsaved text of every open document."""
        return {os.path.realpath(path_of_uri(document.uri)): document.source
                for document in self.workspace.text_documents.values()}

    # -- analysis ----------------------------------------------------------------------

    def schedule(self, uri: str, delay_s: float | None = None) -> None:
        """Analyse ``uri`` after the debounce, replacing an analysis not yet started."""
        old = self.pending.pop(uri, None)
        if old is not None:
            old.cancel()
        delay = self.debounce_s if delay_s is None else delay_s
        self.pending[uri] = asyncio.ensure_future(self._analyse(uri, delay))

    def schedule_dependents(self, uri: str) -> None:
        """Analyse again every other open document that reads ``uri`` through an import."""
        path = self.state(uri).path
        for other, state in list(self.states.items()):
            if other != uri and self.opened(other) \
                    and state.analysis is not None and depends_on(state.analysis, path):
                self.schedule(other)

    async def _analyse(self, uri: str, delay_s: float) -> None:
        if delay_s > 0:
            await asyncio.sleep(delay_s)
        if not self.opened(uri):
            return
        version, text = self.doc_version(uri), self.doc_text(uri)
        state = self.state(uri)
        buffers = self.buffers()
        loop = asyncio.get_running_loop()
        analysis = await loop.run_in_executor(self.executor, self._analysis, state.path, text,
                                              buffers)
        if not self.opened(uri) or self.doc_version(uri) != version:
            return  # superseded: the change that made it stale has its own analysis
        state.analysis, state.analysed_version = analysis, version
        if analysis.program is not None:
            state.parsed = analysis
        self.publish(uri)

    def _analysis(self, path: str, text: str, buffers: dict[str, str]) -> Analysis:
        """One analysis, on the worker thread; never raises."""
        try:
            host = self.host()
            analysis = analyze(path, text, buffer_reader(buffers), host)
        except Exception as error:  # noqa: BLE001 - a bug must not end the server
            logger.exception("analysis of %s failed", path)
            return Analysis(path, text, problems=(Problem(
                Severity.ERROR, f"internal error while analysing ({type(error).__name__}: "
                f"{error}); this is a bug, please report it", SourceLocation(path, 1, 1)),))
        if analysis.program is not None and _uses_plugins(analysis):
            analysis = Analysis(analysis.path, analysis.text, analysis.program, analysis.source,
                                analysis.problems + tuple(
                                    Problem(p.severity, p.message, SourceLocation(path, 1, 1))
                                    for p in self._host_problems),
                                analysis.imported)
        return analysis

    def host(self):
        """The plugin host, loaded once; a plugin that fails is one problem, not a dead
        server (see :attr:`_host_problems`)."""
        with self._host_lock:
            if not self._host_loaded:
                self._load_host()
        return self._host

    def _load_host(self) -> None:
        from orccad_app.plugin_host.host import PluginHost

        self._host_loaded = True
        try:
            self._host = PluginHost.load()
            self._host_problems = tuple(Problem(Severity.WARNING, failure.format(), None)
                                        for failure in self._host.failures)
        except Exception as error:  # noqa: BLE001 - the plugin machinery itself failed
            logger.exception("loading the plugins failed")
            self._host_problems = (Problem(
                Severity.ERROR, f"the plugins could not be loaded: "
                f"{type(error).__name__}: {error}", None),)

    # -- publishing --------------------------------------------------------------------

    def publish(self, uri: str) -> None:
        """Publish ``uri``'s diagnostics (its analysis and the extra ones, such as the
        proof's verdicts), and those it found in imported files that are not open."""
        state = self.state(uri)
        analysis = state.analysis
        if analysis is None:
            return
        by_uri = diagnostics_by_uri(state.path, analysis.text, analysis.problems,
                                    text_of(self.buffers()), self.encoding)
        by_uri[uri] = by_uri.get(uri, []) + self.extra.get(uri, [])
        open_uris = {document.uri for document in self.workspace.text_documents.values()}
        for target, diagnostics in by_uri.items():
            if target != uri and (target in open_uris or self._is_open(target)):
                continue  # an open file publishes its own
            self.text_document_publish_diagnostics(types.PublishDiagnosticsParams(
                uri=target, diagnostics=diagnostics,
                version=state.analysed_version if target == uri else None))
        now = set(by_uri) - {uri}
        for gone in self.foreign.get(uri, set()) - now:
            if not self._is_open(gone):
                self.text_document_publish_diagnostics(
                    types.PublishDiagnosticsParams(uri=gone, diagnostics=[]))
        self.foreign[uri] = now

    def _is_open(self, uri: str) -> bool:
        path = path_of_uri(uri)
        return any(same_file(path_of_uri(document.uri), path)
                   for document in self.workspace.text_documents.values())

    def changed(self, uri: str) -> None:
        """The editor changed ``uri``: what was judged on the old text no longer holds
        (the proof's verdicts are dropped, a running proof is cancelled)."""
        self.extra.pop(uri, None)
        self.verdicts.pop(uri, None)
        if self.proofs.cancel(uri):
            self.log(f"proof of {uri} cancelled: the document changed")

    def log(self, message: str) -> None:
        """A line in the editor's log of this server (``window/logMessage``)."""
        self.window_log_message(types.LogMessageParams(types.MessageType.Info, message))

    # -- the proof ---------------------------------------------------------------------

    def verdict_text(self, uri: str):
        """``(mission, property) -> the last verdict's text`` for the hover of ``uri``."""
        verdicts = self.verdicts.get(uri, {})

        def text(mission: str | None, name: str) -> str | None:
            verdict = verdicts.get((mission, name))
            return None if verdict is None else verdict.text()

        return text

    def prove(self, uri: str) -> str:
        """Start the proof of ``uri``'s current text; what was done, in words."""
        state = self.state(uri)
        analysis = state.analysis
        text = self.doc_text(uri)
        if analysis is None or analysis.text != text or not analysis.checked:
            message = f"proof of {uri} not started: the document has errors (or is being analysed)"
            self.log(message)
            return message
        version = self.doc_version(uri)
        program = analysis.program
        assert program is not None

        def done(answer: dict) -> None:
            if not self.opened(uri) or self.doc_version(uri) != version:
                return
            self._proved(uri, state.path, program, answer)

        def started(pid: int) -> None:
            self.log(f"proof of {uri} started (process {pid})")

        self.proofs.start(uri, state.path, text, self.buffers(), done, started)
        return f"proof of {uri} started"

    def _proved(self, uri: str, path: str, program, answer: dict) -> None:
        lines = self.doc_lines(uri)
        error = answer.get("error")
        if error is not None:
            where = SourceLocation(path, max(error.get("line") or 1, 1),
                                   max(error.get("col") or 1, 1))
            located = error.get("file") is not None  # a compile error, not a budget
            self.extra[uri] = [types.Diagnostic(
                to_range(where, lines), error["message"], source=SOURCE, code="proof",
                severity=types.DiagnosticSeverity.Error if located
                else types.DiagnosticSeverity.Warning)]
            self.log(f"proof of {uri} not done: {error['message']}")
        else:
            verdicts = verdicts_of(path, program, answer)
            self.verdicts[uri] = {(v.mission, v.name): v for v in verdicts}
            self.extra[uri] = verdict_diagnostics(program, verdicts, lines, path)
            false = sum(v.state == "false" for v in verdicts)
            self.log(f"proof of {uri} done: {len(verdicts)} properties, {false} false")
        self.publish(uri)

    def close(self, uri: str) -> None:
        """Forget ``uri`` and clear what it published."""
        task = self.pending.pop(uri, None)
        if task is not None:
            task.cancel()
        self.states.pop(uri, None)
        self.extra.pop(uri, None)
        for target in {uri, *self.foreign.pop(uri, set())}:
            self.text_document_publish_diagnostics(
                types.PublishDiagnosticsParams(uri=target, diagnostics=[]))


def _uses_plugins(analysis: Analysis) -> bool:
    """Whether the document needs the plugins' registries (robots or Robot-Tasks)."""
    program = analysis.program
    return program is not None and bool(program.robots or program.robottasks)


def build_server(debounce_s: float = DEBOUNCE_S,
                 proof_budget_s: float = 60.0) -> OrccadLanguageServer:
    """A server with every feature registered."""
    from orccad_app.lsp import features

    server = OrccadLanguageServer(debounce_s, proof_budget_s)
    features.register(server)
    return server


def serve(debounce_s: float = DEBOUNCE_S, proof_budget_s: float = 60.0) -> int:
    """Serve over stdio until the client says ``exit``; the exit status (the LSP's: 0 when
    ``shutdown`` came before ``exit``, else 1; 0 when the editor closes the stream). The
    protocol owns the real stdout: anything else printing (a plugin, a library) goes to
    stderr instead, where the log is one line per event (:mod:`.logs`)."""
    import sys

    from pygls.io_ import StdoutWriter

    from orccad_app.lsp.logs import log_in_lines
    from orccad_app.lsp.stream import serve_stream

    protocol_out = os.fdopen(os.dup(sys.stdout.fileno()), "wb")
    os.dup2(sys.stderr.fileno(), sys.stdout.fileno())
    sys.stdout = sys.stderr
    log_in_lines()
    server = build_server(debounce_s, proof_budget_s)
    server.protocol.set_writer(StdoutWriter(protocol_out))
    try:
        return asyncio.run(serve_stream(server.protocol, sys.stdin.buffer))
    finally:
        server.executor.shutdown(wait=False, cancel_futures=True)
        try:
            protocol_out.close()
        except OSError:  # the editor stopped reading: nothing is left to flush to
            pass
