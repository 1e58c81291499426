"""Trace files: CSV (one row per event) and MCAP (one JSON message per event).

Both are written as the run goes and closed in a ``finally``: a run that fails or is
interrupted (Ctrl-C) leaves a valid file holding every event up to that point.

**CSV** — header ``time_ns,event,module,port,job,value``; rows as
:class:`~orccad_app.trace.recorder.TraceRow` (``value`` is JSON text, quoted by the CSV rules).

**MCAP** — topics Foxglove plots at once, one per port or plant signal with a stable numeric
schema, the event log as ``foxglove.Log``: see :mod:`orccad_app.trace.mcap_writer`.
"""

from __future__ import annotations

import csv
from pathlib import Path
from typing import IO, Any, Mapping

from orccad_app.diagnostics import OrccadError
from orccad_app.trace.mcap_writer import McapTraceWriter
from orccad_app.trace.recorder import TraceRow

__all__ = ["CsvTraceWriter", "McapTraceWriter", "open_trace", "TRACE_FORMATS", "sensor_ports"]

TRACE_FORMATS = (".csv", ".mcap")
"""File suffixes :func:`open_trace` knows."""



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


def _open(path: str | Path, mode: str, **kwargs: Any) -> IO[Any]:
    try:
        return open(path, mode, **kwargs)
    except OSError as error:
        raise OrccadError(f"cannot write the trace {path}: {error.strerror}") from None


def open_trace(path: str | Path, metadata: Mapping[str, str] | None = None,
               sensors: Mapping[tuple[str, str], str] | None = None,
               trace_format: str | None = None) -> Any:
    """A writer for ``path``, chosen by ``trace_format`` (``csv`` or ``mcap``) or else by its
    suffix (``.csv`` or ``.mcap``); ``sensors`` maps the ``(module, port)`` inputs fed by robot
    sensors to them, for MCAP's ``/plant`` topics (see :func:`sensor_ports`). (A rosbag2
    directory is :class:`orccad_app.ros2.bag.Rosbag2TraceWriter`, above this layer.)"""
    suffix = f".{trace_format}" if trace_format else Path(path).suffix.lower()
    if suffix == ".csv":
        return CsvTraceWriter(path)
    if suffix == ".mcap":
        return McapTraceWriter(path, metadata, sensors, opener=_open)
    raise OrccadError(f"--trace {path}: unknown trace format '{suffix or '(none)'}' "
                      f"(use {' or '.join(TRACE_FORMATS)})")


def sensor_ports(plan: Any) -> dict[tuple[str, str], str]:
    """``(module, port)`` of every input of ``plan``'s TCS fed by a robot sensor -> the sensor
    (``("TrackPID.ctrl", "q") -> "arm.q"``)."""
    robots = {resource.name for resource in plan.tcs.resources}
    return {(c.target.module, c.target.port): c.producer for c in plan.tcs.connections
            if c.source.module in robots}
