"""The port and timing vocabulary shared by module kinds, robots and the TCS.

A :class:`PortSpec` is a typed port as a module kind or a robot type declares it, with a
:class:`PortDirection`; the TCS's :class:`~orccad_app.tcs.port.Port` is the same port placed
in a Robot-Task's TCS (same direction enum, plus its connection-level initial value; the
mission layer converts one into the other). A robot's
:class:`~orccad_app.control.robot.RobotPort` is a ``PortSpec`` bound to MJCF sensors or
actuators. :class:`Timing` is a Module-Task's period and execution times.

This module imports nothing else of :mod:`orccad_app.control` but its errors.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import StrEnum
from typing import Any

import numpy as np

from orccad_app.control.errors import ControlError, DimensionMismatch

__all__ = ["PORT_TYPES", "PortDirection", "PortSpec", "Timing", "TASK_ERROR"]

#: Value types a port can carry. ``vector`` values are ``numpy.ndarray`` of length ``dim``.
PORT_TYPES: tuple[str, ...] = ("vector", "float", "bool", "event", "string")

TASK_ERROR = "e"
"""The task-error port: the ``e`` output of a Robot-Task's control law, :math:`e(q, t)` (RR-1801
eq. 5; a vector of the task's dimension, in the task function's unit), read by the observers
that watch it, recorded as the run's tracking error and written ``robot.e`` in signal
properties."""


class PortDirection(StrEnum):
    """Which way a port's values flow, seen from its owner (a module, a robot, a
    Module-Task of the TCS)."""

    IN = "in"
    """The owner reads it (a module's input, read at the start of each job; a robot's
    actuator)."""
    OUT = "out"
    """The owner writes it (a module's output, written at the end of each job's compute
    phase; a robot's sensor)."""


@dataclass(frozen=True, slots=True)
class PortSpec:
    """A typed port of a module kind or robot.

    ``direction`` is :attr:`PortDirection.IN` (the module reads it) or
    :attr:`PortDirection.OUT` (it writes it; ``"in"``/``"out"`` are accepted and converted). A robot's
    sensors are ``out`` ports (``arm.q -> ctrl.q``) and its actuators ``in`` ports
    (``ctrl.tau -> arm.tau``). ``dim`` is the length of a ``vector`` port; ``None`` in a
    kind's declaration means "fixed at creation" (the robot's number of joints, the task
    function's dimension); instances always carry concrete dims. An input with
    ``required=False`` may stay unconnected: the module then falls back to a documented
    default (e.g. velocity estimated by differences).
    """

    name: str
    direction: PortDirection
    type: str
    dim: int | None = None
    required: bool = True
    doc: str = ""

    def __post_init__(self) -> None:
        if self.direction not in ("in", "out"):
            raise ControlError(f"port {self.name!r}: direction must be 'in' or 'out', "
                               f"got {self.direction!r}")
        object.__setattr__(self, "direction", PortDirection(self.direction))
        if self.type not in PORT_TYPES:
            raise ControlError(f"port {self.name!r}: type must be one of "
                               f"{', '.join(PORT_TYPES)}, got {self.type!r}")
        if self.dim is not None and (self.type != "vector" or self.dim < 1):
            raise ControlError(f"port {self.name!r}: dim {self.dim!r} needs a vector "
                               "type and a positive size")

    @property
    def is_output(self) -> bool:
        """Does the owner write it?"""
        return self.direction is PortDirection.OUT

    def with_dim(self, dim: int | None) -> PortSpec:
        """A copy with ``dim`` set (vector ports only; other types stay dimensionless)."""
        if self.type != "vector":
            return self
        return PortSpec(self.name, self.direction, self.type, dim, self.required, self.doc)

    def check_value(self, value: Any) -> None:
        """Raise :class:`DimensionMismatch` if ``value`` does not fit this port."""
        if self.type == "vector" and self.dim is not None:
            size = np.asarray(value).shape
            if size != (self.dim,):
                raise DimensionMismatch(
                    f"port {self.name!r} expects a vector of {self.dim}, got shape {size}")


@dataclass(frozen=True, slots=True)
class Timing:
    """Timing of a Module-Task: ``period_ns``, ``wcet_ns`` and optional ``bcet_ns`` [ns].

    With ``bcet_ns`` the executive may draw execution times in ``[bcet_ns, wcet_ns]``.
    """

    period_ns: int
    wcet_ns: int
    bcet_ns: int | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.period_ns, int) or self.period_ns <= 0:
            raise ControlError(f"timing: period_ns must be a positive integer, "
                               f"got {self.period_ns!r}")
        if not isinstance(self.wcet_ns, int) or self.wcet_ns < 0:
            raise ControlError(f"timing: wcet_ns must be a non-negative integer, "
                               f"got {self.wcet_ns!r}")
        if self.bcet_ns is not None and not 0 <= self.bcet_ns <= self.wcet_ns:
            raise ControlError(f"timing: bcet_ns must be in [0, wcet_ns={self.wcet_ns}], "
                               f"got {self.bcet_ns!r}")

    @classmethod
    def from_ms(cls, period_ms: float, wcet_ms: float, bcet_ms: float | None = None) -> Timing:
        """Build from milliseconds (rounded to the nanosecond)."""
        bcet = None if bcet_ms is None else round(bcet_ms * 1e6)
        return cls(round(period_ms * 1e6), round(wcet_ms * 1e6), bcet)
