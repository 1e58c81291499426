"""Fuzzing the language server's byte stream (issue 34): generated and hostile frames through
the server's own reader and the real handlers, in process (no subprocess per example).

Promises checked: the loop never raises and ends at the end of the stream; every byte it
writes is a well-framed JSON-RPC message; no request is answered with an internal error (a
bug); and after any sequence of complete frames, however hostile, a request is answered and
``shutdown`` + ``exit`` end the server with 0. The default run has a small budget; ``-m
fuzz_long`` runs the same properties with hundreds of examples."""

from __future__ import annotations

import asyncio
import io
import json
from typing import Any

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

pytest.importorskip("pygls")

from orccad_app.lsp.framing import encode  # noqa: E402
from orccad_app.lsp.server import build_server  # noqa: E402
from orccad_app.lsp.stream import serve_stream  # noqa: E402

DOC = "file:///tmp/orccad-fuzz-lsp/m.orc"
INITIALIZE = encode({"jsonrpc": "2.0", "id": "init", "method": "initialize",
                     "params": {"processId": None, "rootUri": None, "capabilities": {}}})
OPEN = encode({"jsonrpc": "2.0", "method": "textDocument/didOpen", "params": {"textDocument": {
    "uri": DOC, "languageId": "orccad", "version": 1,
    "text": "input Go;\noutput Done;\nmission M { await Go; emit Done; }\n"}}})
PROBE = encode({"jsonrpc": "2.0", "id": "probe", "method": "textDocument/documentSymbol",
                "params": {"textDocument": {"uri": DOC}}})
END = encode({"jsonrpc": "2.0", "id": "bye", "method": "shutdown"}) \
    + encode({"jsonrpc": "2.0", "method": "exit"})


class _Writer:
    """pygls's writer interface over a byte buffer."""

    def __init__(self) -> None:
        self.data = io.BytesIO()

    def write(self, data: bytes) -> None:
        self.data.write(data)

    def close(self) -> None:
        pass


def _serve(stream: bytes) -> tuple[int, list[dict[str, Any]]]:
    """The exit status and every message the server wrote for ``stream``."""
    server = build_server(debounce_s=0.0)
    writer = _Writer()
    server.protocol.set_writer(writer)
    try:
        status = asyncio.run(serve_stream(server.protocol, io.BytesIO(stream)))
    finally:
        server.executor.shutdown(wait=True, cancel_futures=True)
    return status, _frames(writer.data.getvalue())


def _frames(out: bytes) -> list[dict[str, Any]]:
    """The messages of ``out``; fails on anything that is not a well-framed JSON object."""
    found = []
    while out:
        head, separator, rest = out.partition(b"\r\n\r\n")
        assert separator, f"an unframed tail: {out[:80]!r}"
        lengths = [int(line.split(b":", 1)[1]) for line in head.split(b"\r\n")
                   if line.lower().startswith(b"content-length:")]
        assert len(lengths) == 1, head
        body, out = rest[:lengths[0]], rest[lengths[0]:]
        message = json.loads(body)
        assert isinstance(message, dict) and message.get("jsonrpc") == "2.0", message
        found.append(message)
    return found


def _no_internal_error(messages: list[dict[str, Any]]) -> None:
    for message in messages:
        error = message.get("error")
        assert error is None or error["code"] != -32603, message


_JSON = st.recursive(
    st.none() | st.booleans() | st.integers(-2**40, 2**40) | st.floats(allow_nan=False)
    | st.text(max_size=20),
    lambda inner: st.lists(inner, max_size=4) | st.dictionaries(st.text(max_size=8), inner,
                                                                 max_size=4),
    max_leaves=12)
_INTS = st.one_of(st.integers(0, 40), st.sampled_from([-1, 2**31 - 1, 2**31, 2**63]),
                  st.integers(-2**40, 2**40))
# mostly the open document and well-formed positions, so that the handlers' own code runs
_URIS = st.sampled_from([DOC] * 8 + ["file:///dev/zero", "file:///tmp/nope.orc", "untitled:1",
                                     "file:///tmp/a%20b.orc", "", "http://x/y.orc",
                                     "file://%zz"])
_VALID_POSITION = st.fixed_dictionaries({"line": st.integers(0, 40) | _INTS,
                                         "character": st.integers(0, 40) | _INTS})
_POSITION = st.one_of(_VALID_POSITION, _VALID_POSITION, _VALID_POSITION, _JSON)
_METHODS = ["textDocument/hover", "textDocument/definition", "textDocument/completion",
            "textDocument/references", "textDocument/documentSymbol",
            "textDocument/foldingRange", "workspace/executeCommand", "textDocument/didOpen",
            "textDocument/didChange", "textDocument/didClose", "textDocument/didSave",
            "$/cancelRequest", "orccad/unknown", "initialize", "initialized"]


@st.composite
def _params(draw, method: str) -> Any:
    document = {"uri": draw(_URIS)}
    if method == "workspace/executeCommand":
        return {"command": draw(st.sampled_from(["orccad.check", "nope"])),
                "arguments": draw(st.lists(_URIS | _JSON, max_size=3) | st.none())}
    if method == "textDocument/didOpen":
        return {"textDocument": {**document, "languageId": "orccad", "version": draw(_INTS),
                                 "text": draw(st.text(max_size=200))}}
    if method == "textDocument/didChange":
        change = draw(st.fixed_dictionaries({"text": st.text(max_size=40)}) | st.fixed_dictionaries(
            {"range": st.fixed_dictionaries({"start": _POSITION, "end": _POSITION}),
             "text": st.text(max_size=40)}))
        return {"textDocument": {**document, "version": draw(_INTS)},
                "contentChanges": [change]}
    if method == "$/cancelRequest":
        return {"id": draw(_INTS | st.text(max_size=5))}
    return {"textDocument": document, "position": draw(_POSITION),
            "context": {"includeDeclaration": True, "triggerKind": 1}}


@st.composite
def _message(draw) -> dict[str, Any]:
    method = draw(st.sampled_from(_METHODS))
    message: dict[str, Any] = {"jsonrpc": "2.0", "method": method}
    if draw(st.integers(0, 3)) > 0:  # mostly requests: their answers are checked
        message["id"] = draw(st.integers(1, 10**6) | st.text(min_size=1, max_size=6))
    message["params"] = draw(st.one_of(_params(method), _params(method), _params(method),
                                       _JSON))
    return message


_HEADERS = st.sampled_from([b"Content-Length: -5", b"Content-Length: abc", b"Content-Length: ",
                            b"Content-Length: 99999999999999999999", b"Content-Type: x",
                            b"X: y", b"content-length: 1e3"])


@st.composite
def _complete_frame(draw) -> bytes:
    """One chunk that ends where it says: a message (hostile params), a body of any bytes
    framed by its true length, or a bad header block with a short body."""
    kind = draw(st.sampled_from(["message", "body", "header"]))
    if kind == "message":
        return encode(draw(_message()))
    if kind == "body":
        body = draw(st.binary(max_size=60) | _JSON.map(lambda v: json.dumps(v).encode()))
        return f"Content-Length: {len(body)}\r\n\r\n".encode() + body
    junk = draw(st.binary(max_size=20).filter(lambda b: b"ength" not in b.lower()))
    return draw(_HEADERS) + b"\r\n\r\n" + junk


def _settings(examples: int):
    return settings(max_examples=examples, deadline=None, database=None,
                    suppress_health_check=list(HealthCheck))


def _complete_frames(examples: int):
    @_settings(examples)
    @given(st.lists(_complete_frame(), max_size=8))
    def run(chunks):
        status, messages = _serve(INITIALIZE + OPEN + b"".join(chunks) + PROBE + END)
        answers = {m.get("id"): m for m in messages if "method" not in m}
        assert "result" in answers["probe"] or answers["probe"]["error"]["code"] == -32602
        assert answers["bye"] == {"jsonrpc": "2.0", "id": "bye", "result": None}
        assert status == 0
        _no_internal_error(messages)
    return run


def _any_bytes(examples: int):
    pieces = st.one_of(st.binary(max_size=40), _complete_frame(), _HEADERS,
                       st.sampled_from([b"\r\n", b"\r\n\r\n", INITIALIZE, OPEN, PROBE]))

    @_settings(examples)
    @given(st.lists(pieces, max_size=10))
    def run(chunks):
        status, messages = _serve(b"".join(chunks))
        assert status in (0, 1)
        _no_internal_error(messages)
    return run


def test_any_sequence_of_hostile_frames_leaves_the_server_answering():
    _complete_frames(40)()


def test_any_byte_stream_is_read_to_its_end_without_a_crash():
    _any_bytes(30)()


@pytest.mark.fuzz_long
def test_long_hostile_frames():
    _complete_frames(400)()


@pytest.mark.fuzz_long
def test_long_byte_streams():
    _any_bytes(400)()
