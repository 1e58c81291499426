"""The trace recorder: an executive observer that writes every event as it happens.

Each event becomes one :class:`TraceRow` ``(time_ns, event, module, port, job, value)`` handed
to a writer (:mod:`orccad_app.trace.writers`) at once, so a trace is written as the run goes:

============  =================  ==============  =====  ===========================================
event         module             port            job    value
============  =================  ==============  =====  ===========================================
release       Module-Task                        index
start         Module-Task                        index  processor
preempt       Module-Task                        index  processor
resume        Module-Task                        index  processor
compute_end   Module-Task                        index  processor
finish        Module-Task                        index  ``{"response_ns", "missed"}``
overrun       Module-Task                        index  index of the unfinished job
block         Module-Task        port                   ``{"op", "protocol"}``
unblock       Module-Task        port                   ``{"op", "blocked_ns"}``
read          Module-Task        input port             the value read (vectors as lists)
write         Module-Task        output port            the value written
signal                           signal name            its value
message       bus                connection             ``{"kind", "queued_ns"}``
activate      Module-Task
kill          Module-Task
param         Module-Task        parameter              the new value
deadlock                                                the cycle of ``module.port``
reaction                                                ``{"inputs", "outputs", "status"}``
task_start    Robot-Task                         site   its arguments ``{param: value}``
task_end      Robot-Task                         site   the outcome
exception     Robot-Task or ""   exception name         its type (1, 2, 3)
update        Module-Task        parameter              ``{"exception", "task", "old", "new",
                                                        "ramp"}``: a type-1 update (``ramp``:
                                                        ``{"start", "end", "duration_s"}`` or null)
============  =================  ==============  =====  ===========================================

Values are strict JSON text (``json.dumps``: floats print exactly, so equal runs give equal
files; a NaN or an infinity is ``null``, see docs/limits.md);
``job`` is ``-1`` where it does not apply. A ``message`` of kind ``event`` is an observer's
signal delivered to its automaton's processor (connection ``module.port -> automaton@cpu``);
the automaton's reactions with a declared time are jobs of module ``automaton@cpu``.
"""

from __future__ import annotations

import json
from typing import Any, NamedTuple, Protocol

import numpy as np

from orccad_app.executive.observer import Observer
from orccad_app.jsonout import plain as strict_plain

__all__ = ["TraceRow", "TraceWriter", "TraceRecorder", "EVENTS", "to_json", "plain_value"]

EVENTS = ("release", "start", "preempt", "resume", "compute_end", "finish", "overrun", "block",
          "unblock", "read", "write", "signal", "message", "activate", "kill", "param",
          "deadlock", "reaction", "task_start", "task_end", "exception", "update")
"""Every event name a trace may hold, in the order of the table above."""


class TraceRow(NamedTuple):
    """One trace event; see the module docstring."""

    time_ns: int
    event: str
    module: str
    port: str
    job: int
    value: str


class TraceWriter(Protocol):
    """Where rows go: CSV or MCAP (:mod:`orccad_app.trace.writers`)."""

    def write(self, row: TraceRow) -> None:
        """Append one row."""

    def close(self) -> None:
        """Finish the file (it stays valid after an interrupted run)."""


def plain_value(value: Any) -> Any:
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, (list, tuple)):
        return [plain_value(item) for item in value]
    if isinstance(value, dict):
        return {str(k): plain_value(v) for k, v in value.items()}
    if value is None or isinstance(value, (bool, int, float, str)):
        return value
    return repr(value)


def to_json(value: Any) -> str:
    """``value`` as compact JSON text (arrays as lists, unknown objects by ``repr``)."""
    if value is None:
        return ""
    plain = plain_value(value)
    try:
        return json.dumps(plain, separators=(",", ":"), allow_nan=False)
    except ValueError:  # a NaN or an infinity (a diverging plant): null, as docs/limits.md says
        return json.dumps(strict_plain(plain), separators=(",", ":"), allow_nan=False)


class TraceRecorder(Observer):
    """Writes every executive and mission event to ``writer`` (see the module docstring).

    :param writer: the trace file's writer.
    """

    def __init__(self, writer: TraceWriter) -> None:
        self.writer = writer
        self.rows = 0
        """Rows written so far."""

    def close(self) -> None:
        """Close the writer (the run ended, or failed)."""
        self.writer.close()

    def _row(self, time_ns: int, event: str, module: str = "", port: str = "",
             job: int = -1, value: Any = None) -> None:
        self.rows += 1
        self.writer.write(TraceRow(time_ns, event, module, port, job, to_json(value)))

    # -- executive ---------------------------------------------------------------------------

    def on_release(self, t_ns: int, module: str, job: int) -> None:
        self._row(t_ns, "release", module, job=job)

    def on_start(self, t_ns: int, module: str, job: int, processor: str) -> None:
        self._row(t_ns, "start", module, job=job, value=processor)

    def on_preempt(self, t_ns: int, module: str, job: int, processor: str) -> None:
        self._row(t_ns, "preempt", module, job=job, value=processor)

    def on_resume(self, t_ns: int, module: str, job: int, processor: str) -> None:
        self._row(t_ns, "resume", module, job=job, value=processor)

    def on_compute_end(self, t_ns: int, module: str, job: int, processor: str) -> None:
        self._row(t_ns, "compute_end", module, job=job, value=processor)

    def on_finish(self, t_ns: int, module: str, job: int, response_ns: int,
                  missed: bool) -> None:
        self._row(t_ns, "finish", module, job=job,
                  value={"response_ns": response_ns, "missed": missed})

    def on_overrun(self, t_ns: int, module: str, job: int) -> None:
        self._row(t_ns, "overrun", module, value=job)

    def on_block(self, t_ns: int, module: str, port: str, operation: str,
                 protocol: str) -> None:
        self._row(t_ns, "block", module, port, value={"op": operation, "protocol": protocol})

    def on_unblock(self, t_ns: int, module: str, port: str, operation: str,
                   blocked_ns: int) -> None:
        self._row(t_ns, "unblock", module, port,
                  value={"op": operation, "blocked_ns": blocked_ns})

    def on_read(self, t_ns: int, module: str, port: str, value: Any) -> None:
        self._row(t_ns, "read", module, port, value=value)

    def on_write(self, t_ns: int, module: str, port: str, value: Any) -> None:
        self._row(t_ns, "write", module, port, value=value)

    def on_signal(self, t_ns: int, name: str, value: Any) -> None:
        self._row(t_ns, "signal", port=name, value=value)

    def on_message(self, t_ns: int, bus: str, kind: str, connection: str,
                   queued_ns: int) -> None:
        self._row(t_ns, "message", bus, connection, value={"kind": kind, "queued_ns": queued_ns})

    def on_activate(self, t_ns: int, module: str) -> None:
        self._row(t_ns, "activate", module)

    def on_kill(self, t_ns: int, module: str) -> None:
        self._row(t_ns, "kill", module)

    def on_param(self, t_ns: int, module: str, name: str, value: Any) -> None:
        self._row(t_ns, "param", module, name, value=value)

    def on_deadlock(self, t_ns: int, cycle: tuple[str, ...]) -> None:
        self._row(t_ns, "deadlock", value=list(cycle))

    # -- mission -----------------------------------------------------------------------------

    def on_reaction(self, t_ns: int, inputs: tuple[str, ...], outputs: tuple[str, ...],
                    status: str) -> None:
        """One reaction of the automaton (only those with inputs or outputs are recorded:
        the periodic ticks that change nothing would drown the trace)."""
        if inputs or outputs:
            self._row(t_ns, "reaction",
                      value={"inputs": list(inputs), "outputs": list(outputs), "status": status})

    def on_task_start(self, t_ns: int, task: str, site: int, args: dict) -> None:
        self._row(t_ns, "task_start", task, job=site, value=args or None)

    def on_task_end(self, t_ns: int, task: str, site: int, outcome: str) -> None:
        self._row(t_ns, "task_end", task, job=site, value=outcome)

    def on_exception(self, record: Any) -> None:
        self._row(record.time_ns, "exception", record.task or "", record.name,
                  value=record.type.number)
        update = record.update
        if update is not None:
            self._row(record.time_ns, "update", update.module, update.param,
                      value={"exception": record.name, "task": record.task,
                             **{k: v for k, v in update.as_dict().items()
                                if k not in ("module", "param")}})
