"""``orccad lsp`` under a hostile byte stream: every bad frame, body or request gets its
JSON-RPC error (or is dropped with one line on standard error), the server keeps answering,
``shutdown`` + ``exit`` ends it with the specification's status, and its standard error
never holds a Python traceback."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from orccad_app.lsp.framing import encode
from tests.lsp.conftest import ROOT

pytest.importorskip("pygls")

SERVER = [sys.executable, "-m", "orccad_app", "lsp"]
INITIALIZE = encode({"jsonrpc": "2.0", "id": "init", "method": "initialize",
                     "params": {"processId": None, "rootUri": None, "capabilities": {}}}) \
    + encode({"jsonrpc": "2.0", "method": "initialized", "params": {}})
SHUTDOWN = encode({"jsonrpc": "2.0", "id": "bye", "method": "shutdown"})
EXIT = encode({"jsonrpc": "2.0", "method": "exit"})
DOC = Path("/tmp/orccad-lsp-stream/small.orc").as_uri()
OPEN = encode({"jsonrpc": "2.0", "method": "textDocument/didOpen", "params": {"textDocument": {
    "uri": DOC, "languageId": "orccad", "version": 1,
    "text": "mission M { output O; emit O; }\n"}}})


def _request(msg_id, method: str, params: dict) -> dict:
    return {"jsonrpc": "2.0", "id": msg_id, "method": method, "params": params}


def _at(line: int, character: int, uri: str = DOC) -> dict:
    return {"textDocument": {"uri": uri}, "position": {"line": line, "character": character}}


def _framed(body: bytes) -> bytes:
    return f"Content-Length: {len(body)}\r\n\r\n".encode() + body


#: (what is sent, the error code of the answer with id null it gets, or None)
HOSTILE = {
    "no Content-Length": (b"\r\n" + json.dumps(_request(7, "shutdown", {})).encode(), -32700),
    "negative Content-Length": (b"Content-Length: -5\r\n\r\n{}", -32700),
    "Content-Length abc": (b"Content-Length: abc\r\n\r\n{}", -32700),
    "absurd Content-Length": (b"Content-Length: 99999999999999999999\r\n\r\n{}", -32700),
    "not JSON": (_framed(b"{not json"), -32700),
    "a JSON array": (_framed(b'[{"jsonrpc": "2.0", "id": 8, "method": "shutdown"}]'), -32600),
    "a JSON number": (_framed(b"42"), -32600),
    "invalid UTF-8": (_framed(b'{"jsonrpc": "2.0", "id": 9, "method": "x\xff"}'), -32700),
    "deep JSON": (_framed(b"[" * 50_000 + b"]" * 50_000), -32700),
}

#: (the request, the error code of its answer)
BAD_REQUESTS = {
    "malformed params": (_request("p1", "textDocument/hover", {"textDocument": 3}), -32602),
    "negative position": (_request("p2", "textDocument/hover", _at(-1, 0)), -32602),
    "position of 2^31": (_request("p3", "textDocument/definition", _at(0, 2**31)), -32602),
    "a document never opened": (_request("p4", "textDocument/hover",
                                         _at(0, 0, "file:///dev/zero")), -32602),
    "a second initialize": (_request("p5", "initialize", {"capabilities": {}}), -32600),
    "an unknown method": (_request("p6", "orccad/nothing", {}), -32601),
}


def _responses(out: bytes) -> list[dict]:
    found = []
    while out:
        head, _, rest = out.partition(b"\r\n\r\n")
        length = next(int(line.split(b":")[1]) for line in head.split(b"\r\n")
                      if line.lower().startswith(b"content-length:"))
        found.append(json.loads(rest[:length]))
        out = rest[length:]
    return found


def _serve(stream: bytes, timeout_s: float = 60) -> tuple[int, list[dict], str]:
    env = {**os.environ, "ORCCAD_DEBUG": ""}
    done = subprocess.run(SERVER, input=stream, capture_output=True, cwd=ROOT, env=env,
                          timeout=timeout_s)
    return done.returncode, _responses(done.stdout), done.stderr.decode(errors="replace")


def _probe(number: int) -> bytes:
    return encode(_request(f"probe{number}", "textDocument/documentSymbol",
                           {"textDocument": {"uri": DOC}}))


def test_a_hostile_stream_gets_its_errors_and_the_server_keeps_answering():
    stream = INITIALIZE + OPEN
    for number, (sent, _) in enumerate(HOSTILE.values()):
        stream += sent + _probe(number)
    for request, _ in BAD_REQUESTS.values():
        stream += encode(request)
    stream += _probe(99) + SHUTDOWN + encode(_request("late", "textDocument/hover",
                                                        _at(0, 0))) + EXIT
    status, responses, err = _serve(stream)
    assert status == 0, err
    by_id = {r["id"]: r for r in responses if r.get("id") is not None}
    for number in (*range(len(HOSTILE)), 99):
        assert [s["name"] for s in by_id[f"probe{number}"]["result"]] == ["M"]
    null_id = [r["error"]["code"] for r in responses if r.get("id") is None]
    assert null_id == [code for _, code in HOSTILE.values()]
    for name, (request, code) in BAD_REQUESTS.items():
        assert by_id[request["id"]]["error"]["code"] == code, name
    assert "2147483648" in by_id["p3"]["error"]["message"]
    assert "not an open document" in by_id["p4"]["error"]["message"]
    assert by_id["bye"]["result"] is None
    assert by_id["late"]["error"]["code"] == -32600  # after shutdown
    assert "Traceback" not in err
    assert all(line.startswith("orccad lsp: ") for line in err.splitlines()), err


def test_requests_before_initialize_are_refused_and_exit_without_shutdown_is_1():
    stream = encode(_request(1, "textDocument/hover", _at(0, 0))) + OPEN + INITIALIZE \
        + encode(_request(2, "textDocument/documentSymbol", {"textDocument": {"uri": DOC}})) \
        + EXIT
    status, responses, err = _serve(stream)
    assert status == 1
    by_id = {r["id"]: r for r in responses}
    assert by_id[1]["error"]["code"] == -32002
    assert "capabilities" in by_id["init"]["result"]
    # the didOpen before initialize was dropped: the document is not open
    assert by_id[2]["error"]["code"] == -32602
    assert "Traceback" not in err and "dropped" in err


def test_shutdown_then_exit_is_0_and_the_end_of_the_stream_ends_it_too():
    assert _serve(INITIALIZE + SHUTDOWN + EXIT)[0] == 0
    status, responses, err = _serve(INITIALIZE + OPEN)
    assert status == 0 and "Traceback" not in err
