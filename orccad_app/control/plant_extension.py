"""The plant extension a robot type may provide: extra physics, sensor ports, named faults.

A robot type (:class:`~orccad_app.control.robot.RobotType`) whose ``plant_extension()``
returns an instance gets it attached to its plant for each run
(:class:`~orccad_app.executive.plant.MujocoPlant` calls :meth:`PlantExtension.step` before
every integration step and reads its sensor ports like MJCF sensors).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Mapping

import numpy as np

from orccad_app.diagnostics import OrccadError

__all__ = ["PlantExtension", "FaultRange"]


@dataclass(frozen=True)
class FaultRange:
    """The values a fault accepts: a finite number in ``[low, high]`` (in the fault's unit);
    ``flag`` faults accept 0 or 1 (``true``/``false``) only."""

    low: float = -math.inf
    high: float = math.inf
    flag: bool = False

    def check(self, fault: str, value: Any) -> float:
        """``value`` as a float; raise :class:`OrccadError` naming the fault and its range."""
        if isinstance(value, bool) or value is None:
            number = 1.0 if value is None else float(value)
        elif isinstance(value, (int, float)):
            number = float(value)
        else:
            raise OrccadError(f"fault '{fault}': expected a number, got {value!r}")
        if self.flag:
            if number not in (0.0, 1.0):
                raise OrccadError(f"fault '{fault}': expected 0 or 1 (false/true), got {value!r}")
            return number
        if not math.isfinite(number) or not self.low <= number <= self.high:
            raise OrccadError(f"fault '{fault}': value {value!r} out of its range "
                              f"[{self.low:g}, {self.high:g}]")
        return number


FLAG = FaultRange(flag=True)
"""The range of an on/off fault (``leak``, ``gps_denied``…)."""
ANY_FINITE = FaultRange()
"""The range of a fault that accepts any finite number (the default)."""


class PlantExtension:
    """Extra physics, sensor ports and faults of a plant (a robot type's plugin provides it).

    Subclasses set :attr:`sensors` (port -> dim), :attr:`faults` (fault -> description
    with its unit) and :attr:`fault_ranges` (fault -> :class:`FaultRange`; a fault without
    one accepts any finite number) and override the methods; the defaults do nothing.
    ``orccad run --inject`` and the TUI both check a value with :meth:`check_fault` before
    the run applies it.
    """

    sensors: Mapping[str, int] = {}
    faults: Mapping[str, str] = {}
    fault_ranges: Mapping[str, FaultRange] = {}

    def check_fault(self, fault: str, value: Any) -> float:
        """``value`` checked against the range of ``fault`` (see :class:`FaultRange`)."""
        if fault not in self.faults:
            raise OrccadError(f"no fault '{fault}' (faults: {', '.join(self.faults) or 'none'})")
        return self.fault_ranges.get(fault, ANY_FINITE).check(fault, value)

    def bind(self, model: Any, data: Any) -> None:
        """Called once by the plant before the first step (keep ``model``, the
        ``mujoco.MjModel``, and ``data``, its ``mujoco.MjData``)."""

    def step(self, dt_s: float) -> None:
        """Called before each integration step of ``dt_s`` [s]: set ``data.xfrc_applied`` /
        ``qfrc_applied``, integrate the extension's own states (battery energy...)."""

    def read(self, port: str) -> np.ndarray:
        """The value of the sensor ``port`` now (an array; 0-d for a ``float`` port)."""
        raise KeyError(port)

    def inject(self, fault: str, value: Any) -> None:
        """Apply the fault ``fault`` with ``value`` (a name of :attr:`faults`)."""
        raise KeyError(fault)
