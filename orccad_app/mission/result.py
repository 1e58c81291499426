"""What a mission run produced: status, Robot-Task runs, exceptions, executive statistics."""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from orccad_app.executive.simulation import RunStats
from orccad_app.jsonout import plain
from orccad_app.reactive.status import MissionStatus, Status

if TYPE_CHECKING:  # traces read results without the language front end
    from orccad_app.lang.ast_robottask import ExceptionType

_dot = np.dot

__all__ = ["RobotTaskRecord", "ExceptionRecord", "UpdateRecord", "RampRecord", "RunResult",
           "ErrorSamples", "MissionStatus", "STATUSES", "TaskOutcome"]


class TaskOutcome(enum.StrEnum):
    """How a Robot-Task run ended (its value is the word of reports and traces, except
    ``RAISED``, written as the exception's name: :attr:`RobotTaskRecord.outcome`)."""

    RUNNING = Status.RUNNING.value
    """Still running at the end of the run."""
    GOOD_END = "good_end"
    """Ended normally (``X.good_end``)."""
    RAISED = "raised"
    """Ended by an exception (its own type-2/3 one, or the mission's ``Timeout``)."""
    KILLED = "killed"
    """Killed by an enclosing preemption."""


STATUSES = tuple(MissionStatus)
"""Every final status, in :class:`MissionStatus`'s order."""


class ErrorSamples:
    """Running sums of a task error's samples: RMS over samples and components, max."""

    __slots__ = ("sum_sq", "count", "max_abs")

    def __init__(self) -> None:
        self.sum_sq = 0.0
        self.count = 0
        self.max_abs = 0.0

    def add(self, error: Any) -> None:
        """One sample (a vector of components) [rad or m]."""
        if type(error) is np.ndarray and error.ndim == 1 and error.dtype.char == "d":
            values = error  # a control law's e: used as it is
        else:
            values = np.asarray(error, dtype=float).ravel()
        if not values.size:
            return
        square = float(_dot(values, values))  # np.dot: values @ values, cheaper to call
        self.sum_sq += square
        self.count += values.size
        if square != square:  # a NaN component: NaN propagates
            self.max_abs = square
            return
        peak = max(map(abs, values.tolist()))  # as abs(values).max() without NaN
        if peak > self.max_abs:
            self.max_abs = peak

    def summary(self, unit: str = "rad") -> dict[str, Any] | None:
        """``{"rms": …, "max": …, "unit": unit}``, ``None`` without samples."""
        if not self.count:
            return None
        return {"rms": math.sqrt(self.sum_sq / self.count), "max": self.max_abs, "unit": unit}


@dataclass
class RobotTaskRecord:
    """One run of a Robot-Task (a site entered, then left).

    :param name: the Robot-Task.
    :param site: its ``run`` site.
    :param start_ns: when it started [ns].
    :param end_ns: when it ended [ns], ``None`` if still running at the end.
    :param end: how it ended (:class:`TaskOutcome`).
    :param exception: for ``end`` ``RAISED``, the exception that ended it.
    :param errors: the task error's samples (the ``e`` output of its control law).
    :param error_unit: their unit (the task function's: ``rad`` in joint space, ``m`` for a
        Cartesian position).
    :param args: the actual value of each of its parameters at this start (run-time
        arguments evaluated, defaults filled in; vectors as lists).
    """

    name: str
    site: int
    start_ns: int
    end_ns: int | None = None
    end: TaskOutcome = TaskOutcome.RUNNING
    exception: str | None = None
    errors: ErrorSamples = field(default_factory=ErrorSamples)
    error_unit: str = "rad"
    args: dict[str, Any] = field(default_factory=dict)

    @property
    def outcome(self) -> str:
        """The word of reports, traces and observers: ``good_end``, the exception that ended
        it, ``killed`` (an enclosing preemption) or ``running``."""
        if self.end is TaskOutcome.RAISED and self.exception is not None:
            return self.exception
        return self.end.value

    def as_dict(self) -> dict[str, Any]:
        """The JSON form (``tracking_error`` is ``null`` without a control law)."""
        return {"name": self.name, "args": self.args, "start_s": self.start_ns / 1e9,
                "end_s": None if self.end_ns is None else self.end_ns / 1e9,
                "outcome": self.outcome, "tracking_error": self.errors.summary(self.error_unit)}


@dataclass(frozen=True)
class RampRecord:
    """A ramp of a type-1 update: from ``start`` to ``end`` over ``duration_ns`` [ns]."""

    start: Any
    end: Any
    duration_ns: int

    def as_dict(self) -> dict[str, Any]:
        return {"start": plain(self.start), "end": plain(self.end),
                "duration_s": self.duration_ns / 1e9}


@dataclass(frozen=True)
class UpdateRecord:
    """What a type-1 exception changed (RR-1801 §3.4.2).

    :param module: the TCS Module-Task (``TrackPID.ctrl``).
    :param param: its parameter (``kp``).
    :param old: the value before the update.
    :param new: the value set at the update instant (a ramp's start).
    :param ramp: the ramp, if the update is one (the value then moves to its end).
    """

    module: str
    param: str
    old: Any
    new: Any
    ramp: RampRecord | None = None

    def as_dict(self) -> dict[str, Any]:
        return {"module": self.module, "param": self.param, "old": plain(self.old),
                "new": plain(self.new), "ramp": None if self.ramp is None else self.ramp.as_dict()}

    def text(self) -> str:
        """``TrackPID.ctrl.kp 400 -> 600`` or ``… ki 0 -> ramp 0 -> 50 over 1 s``."""
        head = f"{self.module}.{self.param} {_short(self.old)} -> "
        if self.ramp is None:
            return head + _short(self.new)
        ramp = self.ramp
        return head + (f"ramp {_short(ramp.start)} -> {_short(ramp.end)} over "
                       f"{ramp.duration_ns / 1e9:g} s")


def _short(value: Any) -> str:
    value = plain(value)
    if isinstance(value, list):
        return "[" + ", ".join(f"{v:g}" for v in value) + "]"
    return f"{value:g}" if isinstance(value, float) else str(value)


@dataclass(frozen=True)
class ExceptionRecord:
    """An exception raised during the run.

    :param time_ns: when [ns].
    :param name: the exception (``TrackingLost``, ``Timeout``, ``at_rest_timeout``).
    :param type: adjust (1), abort the task (2) or fatal (3), RR-1801 §3.4.2; serialized as
        its ``number``.
    :param task: the Robot-Task that raised it, ``None`` for the mission's own (``within``).
    :param update: for type 1, the parameter update it applied.
    """

    time_ns: int
    name: str
    type: ExceptionType
    task: str | None
    update: UpdateRecord | None = None

    def as_dict(self) -> dict[str, Any]:
        """The JSON form; a type-1 exception's also has ``update``
        (:meth:`UpdateRecord.as_dict`, ``null`` when no task of its was running)."""
        record = {"time_s": self.time_ns / 1e9, "name": self.name, "type": self.type.number,
                  "task": self.task}
        if self.type.number == 1:  # adjust
            record["update"] = None if self.update is None else self.update.as_dict()
        return record


@dataclass
class RunResult:
    """The outcome of :meth:`~orccad_app.mission.run.MissionRun.run`.

    :param mission: the mission's name.
    :param status: one of :data:`STATUSES`.
    :param reason: why it is not ``done`` (exception name, diagnostic), else ``None``.
    :param sim_time_ns: simulated time reached [ns].
    :param wall_time_s: wall-clock duration of the run [s].
    :param robot_tasks: Robot-Task runs in start order.
    :param exceptions: exceptions in time order.
    :param stats: the executive's :class:`~orccad_app.executive.simulation.RunStats`.
    :param modules: TCS Module-Tasks by name (timing attributes for the report).
    :param outputs: mission output signals emitted, ``(t_ns, name, value)``.
    :param lateness_s: paced runs: per instant, lateness behind the wall clock [s].
    :param seed: the run's seed.
    :param interrupted: the run was stopped by Ctrl-C (status ``aborted``).
    """

    mission: str
    status: MissionStatus
    reason: str | None
    sim_time_ns: int
    wall_time_s: float
    robot_tasks: list[RobotTaskRecord]
    exceptions: list[ExceptionRecord]
    stats: RunStats
    modules: dict[str, Any]
    outputs: list[tuple[int, str, Any]] = field(default_factory=list)
    lateness_s: list[float] | None = None
    seed: int = 0
    interrupted: bool = False

    @property
    def exit_status(self) -> int:
        """0 when ``done``, else 1."""
        return 0 if self.status is MissionStatus.DONE else 1

    def rms_error(self, task: str | None = None) -> float | None:
        """RMS tracking error over the runs of ``task`` (default: every run) [rad]."""
        total = ErrorSamples()
        for record in self.robot_tasks:
            if task is None or record.name == task:
                total.sum_sq += record.errors.sum_sq
                total.count += record.errors.count
        summary = total.summary()
        return None if summary is None else summary["rms"]
