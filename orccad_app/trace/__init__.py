"""Traces and reports of executive runs.

:class:`TraceRecorder` observes a run (an executive observer with the mission hooks) and
writes each event at once to a CSV or MCAP file (:func:`open_trace`); :func:`report_dict` and
:func:`format_report` turn a :class:`~orccad_app.mission.result.RunResult` into the JSON
report or the text of ``orccad run``.
"""

from orccad_app.trace.recorder import EVENTS, TraceRecorder, TraceRow, to_json
from orccad_app.trace.run_topics import RunTopicsRecorder, trace_recorder
from orccad_app.trace.state_topics import VerdictSample
from orccad_app.trace.report import (
    InjectionRecord,
    format_report,
    lateness_summary,
    report_dict,
)
from orccad_app.trace.writers import (
    TRACE_FORMATS,
    CsvTraceWriter,
    McapTraceWriter,
    open_trace,
    sensor_ports,
)

__all__ = [
    "TraceRecorder",
    "RunTopicsRecorder",
    "trace_recorder",
    "VerdictSample",
    "TraceRow",
    "EVENTS",
    "to_json",
    "CsvTraceWriter",
    "McapTraceWriter",
    "open_trace",
    "TRACE_FORMATS",
    "sensor_ports",
    "InjectionRecord",
    "report_dict",
    "format_report",
    "lateness_summary",
]
