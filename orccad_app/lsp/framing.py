"""The protocol's base layer: messages framed by a ``Content-Length`` header on a byte stream.

Each message is a header block — ``Name: value`` lines, each ended by ``\\r\\n``, then an
empty line — and a body of exactly ``Content-Length`` bytes (the LSP's base protocol). The
editor's stream is not trusted: :class:`FrameReader` gives either a :class:`Frame` or a
:class:`FramingProblem` for each header block and never raises on what it reads:

- a header block without ``Content-Length``, or with one that is not a decimal number of
  bytes in ``[0, MAX_MESSAGE_BYTES]`` (negative, ``abc``, ``1e3``, twenty digits) is a problem:
  its body, if any, cannot be delimited, so the reader skips what follows up to the next
  ``Content-Length`` header, even one glued to the end of a body without a line break;
- bytes that are no header (a body sent without a header) are skipped the same way and said
  once per block;
- a line is read at most :data:`MAX_LINE_BYTES` at a time, a body at most
  :data:`MAX_MESSAGE_BYTES`: no input makes the reader hold more.

No pygls here (plain bytes and values): the stream loop (:mod:`.stream`) turns each problem
into one line on standard error and one JSON-RPC error.
"""

from __future__ import annotations

import json
import re
from dataclasses import dataclass
from typing import Any, BinaryIO

__all__ = ["Frame", "FramingProblem", "FrameReader", "MAX_MESSAGE_BYTES", "MAX_LINE_BYTES",
           "encode"]

#: The largest body accepted [bytes]: a source file may have 512 kB (docs/limits.md), six
#: times that once JSON escapes every character, with room to spare.
MAX_MESSAGE_BYTES = 64 * 1024 * 1024

#: A header line longer than this is read (and skipped) in pieces of this size [bytes].
MAX_LINE_BYTES = 64 * 1024

_HEADER = re.compile(rb"([!#$%&'*+.^_`|~0-9A-Za-z-]+):[ \t]*(.*?)[ \t]*\r?\n?")
_LENGTH = re.compile(rb"content-length:", re.IGNORECASE)


@dataclass(frozen=True)
class Frame:
    """One message's body, as framed (not yet decoded); ``skipped``: bytes that were no
    header, skipped before its header."""

    body: bytes
    skipped: int = 0


@dataclass(frozen=True)
class FramingProblem:
    """A header block that frames no message: what was wrong, in words."""

    message: str


def _length(value: bytes) -> int | str:
    """The body length of a ``Content-Length`` value, or why it is not one."""
    text = value.decode("ascii", "replace")
    shown = text if len(text) <= 40 else text[:37] + "..."
    if not value.isdigit():
        return f"Content-Length {shown!r} is not a whole number of bytes"
    if len(value) > 12 or int(value) > MAX_MESSAGE_BYTES:
        return (f"Content-Length {shown} is larger than the {MAX_MESSAGE_BYTES} bytes a "
                "message may have")
    return int(value)


class FrameReader:
    """Reads frames from a blocking binary stream (the editor's standard input)."""

    def __init__(self, stream: BinaryIO) -> None:
        self.stream = stream
        self._dropping = False  # bytes skipped now are the body of a dropped message


    def read(self) -> Frame | FramingProblem | None:
        """The next frame or problem; ``None`` at the end of the stream (a message cut by
        it is dropped: nobody is left to answer)."""
        length: int | str | None = None
        skipped = 0
        seen = False  # any line of this block yet (blank lines between messages are not)
        while True:
            line = self.stream.readline(MAX_LINE_BYTES)
            if not line:
                return None
            if not line.strip(b"\r\n"):
                if seen:
                    break
                continue
            seen = True
            if length is not None:
                continue  # the headers after Content-Length (Content-Type) are not needed
            at = _LENGTH.search(line)
            if at is None:
                if _HEADER.fullmatch(line) is None:
                    skipped += len(line)  # not a header: a body without one, or noise
                continue
            skipped += at.start()  # a header glued to the end of unframed bytes
            header = _HEADER.fullmatch(line[at.start():])
            length = _length(header.group(2)) if header is not None \
                else "a Content-Length header cut or malformed"
        return self._framed(length, skipped)

    def _framed(self, length: int | str | None, skipped: int) -> Frame | FramingProblem | None:
        before = f"{skipped} bytes that are no header skipped; " \
            if skipped and not self._dropping else ""
        self._dropping = not isinstance(length, int)
        if length is None:
            return FramingProblem(f"{before}a header without Content-Length: the message "
                                  "is dropped, reading on at the next Content-Length")
        if isinstance(length, str):
            return FramingProblem(f"{before}{length}: the message is dropped, reading on at "
                                  "the next Content-Length")
        body = self.stream.read(length) if length else b""
        if len(body) < length:
            return None
        return Frame(body, 0 if before == "" else skipped)


def encode(message: dict[str, Any]) -> bytes:
    """``message`` framed for the stream (its JSON in ASCII: length in bytes = characters)."""
    body = json.dumps(message, ensure_ascii=True, separators=(",", ":")).encode("ascii")
    return f"Content-Length: {len(body)}\r\n\r\n".encode("ascii") + body
