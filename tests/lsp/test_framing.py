"""The base protocol's framing, the JSON-RPC checks and the lifecycle, without a server:
each hostile header or body is one problem or refusal, and what follows it is read."""

from __future__ import annotations

import io
import json

import pytest

from orccad_app.lsp.framing import (MAX_LINE_BYTES, MAX_MESSAGE_BYTES, Frame, FrameReader,
                                    FramingProblem, encode)
from orccad_app.lsp.jsonrpc import ErrorCode, Incoming, Kind, Refusal, decode
from orccad_app.lsp.lifecycle import Lifecycle, Phase


def frames(data: bytes) -> list[Frame | FramingProblem]:
    reader = FrameReader(io.BytesIO(data))
    out = []
    while (read := reader.read()) is not None:
        out.append(read)
    return out


GOOD = encode({"jsonrpc": "2.0", "id": 1, "method": "shutdown"})


def test_a_well_framed_message_and_its_optional_content_type():
    assert frames(GOOD) == [Frame(GOOD.split(b"\r\n\r\n", 1)[1])]
    typed = b"content-length: 2\r\nContent-Type: application/vscode-jsonrpc; charset=utf-8" \
            b"\r\n\r\n{}"
    assert frames(typed + GOOD)[0] == Frame(b"{}")


@pytest.mark.parametrize("value, said", [
    (b"-5", "'-5' is not a whole number of bytes"),
    (b"abc", "'abc' is not a whole number of bytes"),
    (b"1e3", "'1e3' is not a whole number of bytes"),
    (b"", "'' is not a whole number of bytes"),
    (b"99999999999999999999", "larger than the 67108864 bytes"),
    (str(MAX_MESSAGE_BYTES + 1).encode(), "larger than the 67108864 bytes"),
])
def test_a_bad_content_length_is_one_problem_and_the_next_message_is_read(value, said):
    found = frames(b"Content-Length: " + value + b"\r\n\r\n{\"a\": 1}" + GOOD)
    assert isinstance(found[0], FramingProblem) and said in found[0].message
    assert found[1:] == [Frame(GOOD.split(b"\r\n\r\n", 1)[1])]  # its body: not said again


def test_a_header_without_content_length_is_one_problem():
    found = frames(b"Content-Type: text/plain\r\n\r\n{}\r\n" + GOOD)
    assert isinstance(found[0], FramingProblem)
    assert "without Content-Length" in found[0].message
    assert found[1] == Frame(GOOD.split(b"\r\n\r\n", 1)[1])


def test_a_body_without_header_is_skipped_up_to_the_next_header_glued_to_it():
    body = b'{"jsonrpc": "2.0", "method": "x"}'
    found = frames(b"\r\n" + body + GOOD)
    assert found == [Frame(GOOD.split(b"\r\n\r\n", 1)[1], skipped=len(body))]


def test_a_line_without_end_is_read_in_bounded_pieces():
    noise = b"x" * (3 * MAX_LINE_BYTES + 5)
    assert frames(noise + GOOD) == [Frame(GOOD.split(b"\r\n\r\n", 1)[1],
                                          skipped=len(noise))]


def test_a_message_cut_by_the_end_of_the_stream_is_the_end():
    assert frames(GOOD[:-3]) == []
    assert frames(b"Content-Length: 10\r\n") == []


@pytest.mark.parametrize("body, code, said", [
    (b"{not json", ErrorCode.PARSE_ERROR, "not JSON"),
    (b'{"jsonrpc": "2.0", "method": "x\xff"}', ErrorCode.PARSE_ERROR,
     "not UTF-8 (byte 0xff at offset 31)"),
    (b"[" * 100_000 + b"]" * 100_000, ErrorCode.PARSE_ERROR, "nested too deeply"),
    (b'{"jsonrpc": "2.0", "id": ' + b"9" * 5000 + b', "method": "x"}',
     ErrorCode.PARSE_ERROR, "not JSON"),
    (b"", ErrorCode.PARSE_ERROR, "not JSON"),
    (b"[1, 2, 3]", ErrorCode.INVALID_REQUEST, "a JSON array (a JSON-RPC batch"),
    (b"42", ErrorCode.INVALID_REQUEST, "a JSON number"),
    (b'{"id": 1, "method": "x"}', ErrorCode.INVALID_REQUEST, '"jsonrpc": "2.0" is missing'),
    (b'{"jsonrpc": "2.0", "id": null, "method": "x"}', ErrorCode.INVALID_REQUEST,
     "not null"),
    (b'{"jsonrpc": "2.0", "id": 1.5, "method": "x"}', ErrorCode.INVALID_REQUEST,
     "not a number"),
    (b'{"jsonrpc": "2.0", "id": true, "method": "x"}', ErrorCode.INVALID_REQUEST,
     "not a boolean"),
    (b'{"jsonrpc": "2.0", "id": 1, "method": 7}', ErrorCode.INVALID_REQUEST,
     "a method must be a string"),
    (b'{"jsonrpc": "2.0", "id": 1, "method": "x", "params": 3}', ErrorCode.INVALID_PARAMS,
     "a number, not an object"),
    (b'{"jsonrpc": "2.0"}', ErrorCode.INVALID_REQUEST, "neither a request"),
])
def test_a_body_that_is_no_message_is_refused_with_its_json_rpc_error(body, code, said):
    refused = decode(body)
    assert isinstance(refused, Refusal) and refused.code is code
    assert said in refused.message
    response = refused.response()
    assert response["error"]["code"] == int(code)
    json.dumps(response)  # sendable


def test_a_refusal_is_answered_only_when_someone_waits_for_it():
    request = decode(b'{"jsonrpc": "2.0", "id": 4, "method": 5}')
    assert isinstance(request, Refusal) and request.answered and request.id == 4
    notification = decode(b'{"jsonrpc": "2.0", "method": "x", "params": "p"}')
    assert isinstance(notification, Refusal) and not notification.answered
    response = decode(b'{"id": 4, "result": null}')
    assert isinstance(response, Refusal) and not response.answered
    unknown = decode(b"[]")
    assert isinstance(unknown, Refusal) and unknown.answered and unknown.id is None


def test_well_formed_messages_by_kind():
    assert decode(b'{"jsonrpc": "2.0", "id": "a", "method": "m", "params": {}}') == Incoming(
        {"jsonrpc": "2.0", "id": "a", "method": "m", "params": {}}, Kind.REQUEST, "m", "a")
    notified = decode(b'{"jsonrpc": "2.0", "method": "m"}')
    assert isinstance(notified, Incoming) and notified.kind is Kind.NOTIFICATION
    answered = decode(b'{"jsonrpc": "2.0", "id": 3, "result": [1]}')
    assert isinstance(answered, Incoming) and answered.kind is Kind.RESPONSE


def _message(method: str, msg_id: int | None = 1) -> Incoming:
    kind = Kind.NOTIFICATION if msg_id is None else Kind.REQUEST
    return Incoming({}, kind, method, msg_id)


def test_the_lifecycle_of_the_specification():
    life = Lifecycle()
    early = life.refusal(_message("textDocument/hover"))
    assert early is not None and early.code is ErrorCode.SERVER_NOT_INITIALIZED
    dropped = life.refusal(_message("textDocument/didOpen", None))
    assert dropped is not None and not dropped.answered
    assert life.exit_status() == 1
    assert life.refusal(_message("initialize")) is None
    life.served(_message("initialize"))
    assert life.phase is Phase.RUNNING
    again = life.refusal(_message("initialize"))
    assert again is not None and again.code is ErrorCode.INVALID_REQUEST
    assert life.refusal(_message("shutdown")) is None
    life.served(_message("shutdown"))
    late = life.refusal(_message("textDocument/hover"))
    assert late is not None and late.code is ErrorCode.INVALID_REQUEST
    assert life.exit_status() == 0
