r"""Minimum-jerk point-to-point motion."""

from __future__ import annotations

from typing import Any

import numpy as np

from orccad_app.control.errors import DimensionMismatch, InvalidParameter
from orccad_app.control.trajectories.base import (Sample, Trajectory, frozen_array,
                                                  position_array)

__all__ = ["MinimumJerk"]


class MinimumJerk(Trajectory):
    """From ``start`` to ``goal`` in ``duration`` [s], minimum jerk; then holds ``goal``.

    ``start=None`` takes the start from the first measurement (see :meth:`with_start`).
    """

    name = "min_jerk"

    def __init__(self, goal: Any, duration: float, start: Any = None):
        if not 1e-6 <= duration <= 365 * 24 * 3600.0:  # NaN fails this test too
            raise InvalidParameter(f"min_jerk: duration must be in [1 us, one year] (its "
                                   f"square divides the acceleration), got {duration!r}")
        self.goal = position_array(goal, "min_jerk goal")
        self.duration = float(duration)
        self.start = None if start is None else position_array(start, "min_jerk start")
        if self.start is not None and self.start.shape != self.goal.shape:
            raise DimensionMismatch(f"min_jerk: start has {self.start.size} components "
                                    f"but goal has {self.goal.size}")
        self.end_time_s = self.duration
        self._delta = None if self.start is None else frozen_array(self.goal - self.start)
        self.needs_start = self.start is None

    @property
    def dim(self) -> int:
        return self.goal.size

    def final(self) -> np.ndarray:
        """The goal (known even before the start is)."""
        return self.goal

    def with_start(self, start: np.ndarray) -> Trajectory:
        if not self.needs_start:
            return self
        return MinimumJerk(self.goal, self.duration, np.asarray(start, dtype=float))

    def sample(self, t_s: float) -> Sample:
        if self.start is None:
            raise InvalidParameter("min_jerk: no start position yet (give start=[...] "
                                   "or connect the trajectory module's q input)")
        tau = min(max(t_s / self.duration, 0.0), 1.0)
        s = tau ** 3 * (10.0 - 15.0 * tau + 6.0 * tau ** 2)
        ds = 30.0 * tau ** 2 * (1.0 - tau) ** 2 / self.duration
        dds = 60.0 * tau * (1.0 - tau) * (1.0 - 2.0 * tau) / self.duration ** 2
        delta = self._delta
        return Sample(pos=self.start + s * delta, vel=ds * delta, acc=dds * delta)
