"""A frame's body as a JSON-RPC 2.0 message, checked before any handler sees it.

:func:`decode` gives an :class:`Incoming` message (a request, a notification or a response)
or a :class:`Refusal`: the JSON-RPC error that answers it (``id`` ``null`` when the body has
no usable id, as JSON-RPC says) or, for a notification or a response (never answered), the
line that says it was dropped. Never raises on what the editor sends:

- a body that is not UTF-8 or not JSON (or nested past the parser's depth) is a parse error
  (-32700);
- a JSON array (a JSON-RPC batch: the LSP has none), a number, a string, an object without
  ``"jsonrpc": "2.0"``, an ``id`` that is neither a number nor a string, a ``method`` that is
  not a string, an object that is neither request, notification nor response: an invalid
  request (-32600).

No pygls here (plain values): the stream loop (:mod:`.stream`) structures what passes into
the protocol's types.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from enum import Enum, IntEnum
from typing import Any

__all__ = ["ErrorCode", "Kind", "Incoming", "Refusal", "decode", "error_response"]

MsgId = int | str | None


class ErrorCode(IntEnum):
    """The JSON-RPC and LSP error codes this server answers with."""

    PARSE_ERROR = -32700
    """The body is not JSON (or not UTF-8)."""
    INVALID_REQUEST = -32600
    """JSON, but not a message; or a request the lifecycle does not allow now."""
    METHOD_NOT_FOUND = -32601
    """No handler for the method."""
    INVALID_PARAMS = -32602
    """The params are not those of the method (a missing field, a negative position)."""
    INTERNAL_ERROR = -32603
    """A bug of the server (said on standard error, in one line)."""
    SERVER_NOT_INITIALIZED = -32002
    """A request before ``initialize`` (the LSP's code)."""


class Kind(Enum):
    """What a message is, by its fields (JSON-RPC 2.0)."""

    REQUEST = "request"
    """``method`` and ``id``: answered with a result or an error."""
    NOTIFICATION = "notification"
    """``method``, no ``id``: never answered."""
    RESPONSE = "response"
    """``id`` and ``result`` or ``error``: the answer to one of the server's requests."""


@dataclass(frozen=True)
class Incoming:
    """One well-formed message: its JSON object, kind, method (``None`` for a response)
    and id (``None`` for a notification)."""

    data: dict[str, Any]
    kind: Kind
    method: str | None
    id: MsgId


@dataclass(frozen=True)
class Refusal:
    """A message refused: the error ``code`` and ``message``; ``answered`` when the sender
    waits for an answer (a request, or a body whose kind is unknown: id ``null``)."""

    code: ErrorCode
    message: str
    id: MsgId = None
    answered: bool = True

    def response(self) -> dict[str, Any]:
        """The JSON-RPC error response."""
        return error_response(self.id, self.code, self.message)


def error_response(msg_id: MsgId, code: ErrorCode, message: str) -> dict[str, Any]:
    """A JSON-RPC error response object."""
    return {"jsonrpc": "2.0", "id": msg_id, "error": {"code": int(code), "message": message}}


def _json(body: bytes) -> Any:
    """The JSON value of ``body``, or a parse-error refusal."""
    try:
        text = body.decode("utf-8")
    except UnicodeDecodeError as error:
        return Refusal(ErrorCode.PARSE_ERROR, f"parse error: the body is not UTF-8 (byte "
                                              f"0x{body[error.start]:02x} at offset "
                                              f"{error.start})")
    try:
        return json.loads(text)
    except RecursionError:
        return Refusal(ErrorCode.PARSE_ERROR, "parse error: the body is JSON nested too "
                                              "deeply")
    except ValueError as error:  # JSONDecodeError, or an integer of too many digits
        shown = str(error)
        return Refusal(ErrorCode.PARSE_ERROR, f"parse error: the body is not JSON "
                                              f"({shown[:120]})")


_NOT_OBJECT = {list: "a JSON array (a JSON-RPC batch: the LSP has none; send one message "
                     "per frame)",
               str: "a JSON string", int: "a JSON number", float: "a JSON number",
               bool: "a JSON boolean", type(None): "JSON null"}


def decode(body: bytes) -> Incoming | Refusal:
    """The message in ``body`` or why it is refused (see the module docstring)."""
    data = _json(body)
    if isinstance(data, Refusal):
        return data
    if not isinstance(data, dict):
        return Refusal(ErrorCode.INVALID_REQUEST, f"invalid request: {_NOT_OBJECT[type(data)]}"
                                                  ", not a message object")
    msg_id = data.get("id")
    has_id = "id" in data
    if has_id and (isinstance(msg_id, bool) or not isinstance(msg_id, (int, str))):
        return Refusal(ErrorCode.INVALID_REQUEST, f"invalid request: an id must be a number "
                                                  f"or a string, not {_kind(msg_id)}")
    method = data.get("method")
    # answered: a request (method and id), or a body of no kind (answered with id null);
    # never a notification or a response
    answered = ("method" in data) == has_id
    reply_to = msg_id if "method" in data else None
    if data.get("jsonrpc") != "2.0":
        return Refusal(ErrorCode.INVALID_REQUEST, 'invalid request: "jsonrpc": "2.0" is '
                                                  'missing', reply_to, answered)
    if "method" in data:
        if not isinstance(method, str):
            return Refusal(ErrorCode.INVALID_REQUEST, f"invalid request: a method must be a "
                                                      f"string, not {_kind(method)}", reply_to,
                           answered)
        params = data.get("params")
        if params is not None and not isinstance(params, (dict, list)):
            return Refusal(ErrorCode.INVALID_PARAMS, f"invalid params of {method}: "
                                                     f"{_kind(params)}, not an object",
                           reply_to, answered)
        return Incoming(data, Kind.REQUEST if has_id else Kind.NOTIFICATION, method,
                        msg_id if has_id else None)
    if has_id and ("result" in data) != ("error" in data):
        return Incoming(data, Kind.RESPONSE, None, msg_id)
    return Refusal(ErrorCode.INVALID_REQUEST, "invalid message: neither a request (method "
                                              "and id), a notification (method) nor a "
                                              "response (id and result or error)",
                   None, answered)


def _kind(value: Any) -> str:
    if value is None:
        return "null"
    if isinstance(value, bool):
        return "a boolean"
    if isinstance(value, (int, float)):
        return "a number"
    if isinstance(value, str):
        return "a string"
    return "an array" if isinstance(value, list) else "an object"
