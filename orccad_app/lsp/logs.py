"""What the server writes on standard error: one line per event, never a traceback.

The editor shows the server's standard error in its log of the server. Every record of
every logger (the server's, pygls's, asyncio's) becomes one line ``orccad lsp: LEVEL:
message`` with the exception's type and first line, not its traceback; an exception that
escapes a thread, or cannot be raised, is one such line too. ``ORCCAD_DEBUG=1`` keeps the
tracebacks (to report a bug).
"""

from __future__ import annotations

import logging
import os
import sys
import threading
from typing import Any

__all__ = ["OneLineFormatter", "log_in_lines", "DEBUG_ENV"]

#: The environment variable that keeps tracebacks (as for every ``orccad`` command).
DEBUG_ENV = "ORCCAD_DEBUG"

#: The longest line written [characters].
MAX_LINE_CHARS = 1000


def _first_line(text: str) -> str:
    lines = text.strip().splitlines()
    return lines[0] if lines else ""


class OneLineFormatter(logging.Formatter):
    """``orccad lsp: LEVEL: message (ExceptionType: its first line)``: one line."""

    def format(self, record: logging.LogRecord) -> str:
        line = _first_line(record.getMessage())
        if record.exc_info and record.exc_info[1] is not None:
            error = record.exc_info[1]
            line += f" ({type(error).__name__}: {_first_line(str(error))})"
        line = f"orccad lsp: {record.levelname.lower()}: {line}"
        return line if len(line) <= MAX_LINE_CHARS else line[:MAX_LINE_CHARS - 3] + "..."


def _thread_hook(args: Any) -> None:
    logging.getLogger("orccad_app.lsp").error(
        "thread %s ended by an exception", getattr(args.thread, "name", "?"),
        exc_info=(args.exc_type, args.exc_value, args.exc_traceback))


def _unraisable_hook(unraisable: Any) -> None:
    logging.getLogger("orccad_app.lsp").error(
        "an exception could not be raised (%s)", _first_line(str(unraisable.err_msg or "")),
        exc_info=(type(unraisable.exc_value), unraisable.exc_value, None)
        if unraisable.exc_value is not None else None)


def log_in_lines(level: int = logging.WARNING) -> None:
    """Send every log record to standard error in one line (see the module docstring)."""
    handler = logging.StreamHandler(sys.stderr)
    if os.environ.get(DEBUG_ENV, "") in ("", "0"):
        handler.setFormatter(OneLineFormatter())
        threading.excepthook = _thread_hook
        sys.unraisablehook = _unraisable_hook
    else:
        handler.setFormatter(logging.Formatter("orccad lsp: %(levelname)s: %(name)s: "
                                               "%(message)s"))
    root = logging.getLogger()
    root.handlers[:] = [handler]
    root.setLevel(level)
