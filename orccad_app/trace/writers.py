"""Trace files: CSV (one row per event) and MCAP (one JSON message per event).

Both are written as the run goes and closed in a ``finally``: a run that fails or is
interrupted (Ctrl-C) leaves a valid file holding every event up to that point.

**CSV** — header ``time_ns,event,module,port,job,value``; rows as
:class:`~orccad_app.trace.recorder.TraceRow` (``value`` is JSON text, quoted by the CSV rules).

**MCAP** — one channel per event kind, topic ``/orccad/<event>``, message encoding ``json``
with a JSON Schema; each message is ``{"module", "port", "job", "value"}`` (``value`` parsed
JSON, or ``null``), ``log_time`` = ``publish_time`` = the simulated instant [ns], ``sequence``
the row number. A metadata record ``orccad`` holds the run's description (mission, seed,
file). Read back with ``mcap.reader.make_reader(f).iter_messages()``. Chunks are
zstd-compressed; the output is deterministic (same rows → same bytes).
"""

from __future__ import annotations

import csv
import json
from pathlib import Path
from typing import IO, Any, Mapping

from orccad_app.diagnostics import OrccadError
from orccad_app.trace.recorder import EVENTS, TraceRow

__all__ = ["CsvTraceWriter", "McapTraceWriter", "open_trace", "TRACE_FORMATS", "MESSAGE_SCHEMA"]

TRACE_FORMATS = (".csv", ".mcap")
"""File suffixes :func:`open_trace` knows."""

MESSAGE_SCHEMA = {
    "type": "object",
    "properties": {
        "module": {"type": "string", "description": "Module-Task, bus or Robot-Task"},
        "port": {"type": "string", "description": "port, signal, parameter or exception"},
        "job": {"type": "integer", "description": "job index or run site; -1 if none"},
        "value": {"description": "the event's value (see orccad_app.trace.recorder)"},
    },
}
"""JSON Schema of every MCAP message."""


class CsvTraceWriter:
    """Rows to a CSV file (``time_ns,event,module,port,job,value``)."""

    HEADER = TraceRow._fields

    def __init__(self, path: str | Path) -> None:
        self.path = str(path)
        self._file: IO[str] = _open(path, "w", newline="", encoding="utf-8")
        self._csv = csv.writer(self._file, lineterminator="\n")
        self._csv.writerow(self.HEADER)
        self.write = self._csv.writerow  # a TraceRow is a tuple: no per-row conversion

    def close(self) -> None:
        """Flush and close (idempotent)."""
        if not self._file.closed:
            self._file.close()


class McapTraceWriter:
    """Rows to an MCAP file, one channel per event kind."""

    def __init__(self, path: str | Path, metadata: Mapping[str, str] | None = None) -> None:
        from mcap.writer import Writer

        self.path = str(path)
        self._file: IO[bytes] = _open(path, "wb")
        self._writer = Writer(self._file)
        self._writer.start(profile="", library="orccad")
        schema = self._writer.register_schema("orccad.TraceEvent", "jsonschema",
                                              json.dumps(MESSAGE_SCHEMA).encode())
        self._channels = {event: self._writer.register_channel(f"/orccad/{event}", "json",
                                                               schema)
                          for event in EVENTS}
        if metadata:
            self._writer.add_metadata("orccad", {k: str(v) for k, v in metadata.items()})
        self._sequence = 0
        self._closed = False

    def write(self, row: TraceRow) -> None:
        """Append one row as a message on its event's channel."""
        time_ns, event, module, port, job, value = row
        body = (f'{{"module":{json.dumps(module)},"port":{json.dumps(port)},"job":{job},'
                f'"value":{value or "null"}}}')
        self._sequence += 1
        self._writer.add_message(self._channels[event], time_ns, body.encode(), time_ns,
                                 self._sequence)

    def close(self) -> None:
        """Write the summary and footer, close the file (idempotent)."""
        if not self._closed:
            self._closed = True
            try:
                self._writer.finish()
            finally:
                self._file.close()


def _open(path: str | Path, mode: str, **kwargs: Any) -> IO[Any]:
    try:
        return open(path, mode, **kwargs)
    except OSError as error:
        raise OrccadError(f"cannot write the trace {path}: {error.strerror}") from None


def open_trace(path: str | Path, metadata: Mapping[str, str] | None = None) -> Any:
    """A writer for ``path``, chosen by its suffix (``.csv`` or ``.mcap``)."""
    suffix = Path(path).suffix.lower()
    if suffix == ".csv":
        return CsvTraceWriter(path)
    if suffix == ".mcap":
        return McapTraceWriter(path, metadata)
    raise OrccadError(f"--trace {path}: unknown trace format '{suffix or '(none)'}' "
                      f"(use {' or '.join(TRACE_FORMATS)})")
