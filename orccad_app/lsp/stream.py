"""The server's loop over the editor's byte stream, in place of pygls's reader.

Each frame (:mod:`.framing`) is decoded and checked as a JSON-RPC message (:mod:`.jsonrpc`),
admitted by the lifecycle (:mod:`.lifecycle`), structured into the protocol's types (a
field missing, a position that is negative or not below 2³¹: invalid params, -32602, the
field named) and only then handed to pygls's protocol, which calls the handler. What is
refused is answered with its JSON-RPC error when the sender waits for one (a request, or a
body whose kind is unknown: id ``null``) and said in one line on standard error; the loop
goes on. ``exit`` ends it with the lifecycle's status (0 after ``shutdown``, else 1); the end
of the stream, or an editor that stopped reading, ends it with 0.
"""

from __future__ import annotations

import asyncio
import logging
from concurrent.futures import ThreadPoolExecutor
from typing import Any, BinaryIO

import cattrs
from cattrs.v import format_exception
from pygls.protocol import JsonRPCNotification, JsonRPCRequestMessage, default_converter

from orccad_app.lsp.framing import Frame, FrameReader, FramingProblem, encode
from orccad_app.lsp.jsonrpc import (ErrorCode, Incoming, Kind, Refusal, decode,
                                    error_response)
from orccad_app.lsp.lifecycle import EXIT, Lifecycle

__all__ = ["serve_stream"]

logger = logging.getLogger(__name__)

#: The longest error message sent or logged [characters].
MAX_MESSAGE_CHARS = 400


class _Gone(Exception):
    """The editor stopped reading (a broken pipe): nobody is left to answer."""


async def serve_stream(protocol: Any, stdin: BinaryIO) -> int:
    """Serve the messages of ``stdin`` with pygls's ``protocol`` (its writer set) until
    ``exit`` or the end of the stream; the exit status."""
    reader = FrameReader(stdin)
    lifecycle = Lifecycle()
    converter = default_converter()
    loop = asyncio.get_running_loop()
    with ThreadPoolExecutor(1, thread_name_prefix="orccad-lsp-reader") as reading:
        while True:
            read = await loop.run_in_executor(reading, reader.read)
            if read is None:
                return 0
            try:
                status = _one(protocol, converter, lifecycle, read)
            except _Gone:
                return 0
            if status is not None:
                return status


def _one(protocol: Any, converter: cattrs.Converter, lifecycle: Lifecycle,
         read: Frame | FramingProblem) -> int | None:
    """Serve one frame; the exit status if it was ``exit``."""
    if isinstance(read, FramingProblem):
        _refuse(protocol, Refusal(ErrorCode.PARSE_ERROR, f"parse error: {read.message}"))
        return None
    if read.skipped:
        _refuse(protocol, Refusal(ErrorCode.PARSE_ERROR, f"parse error: {read.skipped} bytes "
                                                         "that are no header skipped (a "
                                                         "message without Content-Length?)"))
    incoming = decode(read.body)
    if isinstance(incoming, Refusal):
        _refuse(protocol, incoming)
        return None
    if incoming.method == EXIT and incoming.kind is Kind.NOTIFICATION:
        return lifecycle.exit_status()
    refusal = lifecycle.refusal(incoming)
    if refusal is not None:
        _refuse(protocol, refusal)
        return None
    message = _structured(protocol, converter, incoming)
    if isinstance(message, Refusal):
        _refuse(protocol, message)
        return None
    lifecycle.served(incoming)
    try:
        protocol.handle_message(message)
    except (BrokenPipeError, ConnectionError):
        raise _Gone from None
    except Exception as error:  # noqa: BLE001 - a bug of a handler must not end the server
        logger.error("%s failed: %s: %s", incoming.method or "a response",
                     type(error).__name__, _short(str(error)))
        if incoming.kind is Kind.REQUEST:
            _send(protocol, error_response(incoming.id, ErrorCode.INTERNAL_ERROR,
                                           f"internal error ({type(error).__name__}); this "
                                           "is a bug, please report it"))
    return None


def _structured(protocol: Any, converter: cattrs.Converter, incoming: Incoming) -> Any:
    """``incoming`` in the protocol's types, or the invalid-params refusal naming the
    fields at fault."""
    if incoming.kind is Kind.RESPONSE:
        try:
            return protocol.structure_message(incoming.data)
        except Exception as error:  # noqa: BLE001 - a malformed answer of the editor
            return Refusal(ErrorCode.INVALID_REQUEST, f"a malformed response to request "
                                                      f"{incoming.id!r}: {error}", None, False)
    fallback = JsonRPCRequestMessage if incoming.kind is Kind.REQUEST else JsonRPCNotification
    target = protocol.get_message_type(incoming.method) or fallback
    try:
        return converter.structure(incoming.data, target)
    except cattrs.ClassValidationError as error:
        why = "; ".join(cattrs.transform_error(error, format_exception=_format))
    except Exception as error:  # noqa: BLE001 - a hook's own error on odd params
        why = f"{type(error).__name__}: {error}"
    return Refusal(ErrorCode.INVALID_PARAMS, f"invalid params of {incoming.method}: {why}",
                   incoming.id, incoming.kind is Kind.REQUEST)


def _format(error: BaseException, type_: Any) -> str:
    """cattrs's words for one field, with a validator's own message (a position's range)."""
    if type(error) is ValueError:
        return f"invalid value ({error})"
    return format_exception(error, type_)


def _refuse(protocol: Any, refusal: Refusal) -> None:
    """Say ``refusal`` on standard error, and answer it when the sender waits for it."""
    message = _short(refusal.message)
    if refusal.answered:
        logger.warning("refused (error %d): %s", int(refusal.code), message)
        _send(protocol, error_response(refusal.id, refusal.code, message))
    else:
        logger.warning("dropped: %s", message)


def _send(protocol: Any, message: dict[str, Any]) -> None:
    try:
        protocol.writer.write(encode(message))
    except (BrokenPipeError, ConnectionError):
        raise _Gone from None


def _short(text: str) -> str:
    text = " ".join(text.split())
    return text if len(text) <= MAX_MESSAGE_CHARS else text[:MAX_MESSAGE_CHARS - 3] + "..."
