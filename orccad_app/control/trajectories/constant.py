"""Holding a position."""

from __future__ import annotations

from typing import Any

import numpy as np

from orccad_app.control.errors import InvalidParameter
from orccad_app.control.trajectories.base import (Sample, Trajectory, frozen_array,
                                                  position_array)

__all__ = ["Constant"]


class Constant(Trajectory):
    """Hold ``value``; ``value=None`` holds the first measured position."""

    name = "constant"
    end_time_s = 0.0

    def __init__(self, value: Any = None, dim: int | None = None):
        self.value = None if value is None else position_array(value, "constant value")
        self._dim = self.value.size if self.value is not None else dim
        self.needs_start = self.value is None
        self._zero = None if self.value is None else frozen_array(np.zeros_like(self.value))

    @property
    def dim(self) -> int:
        if self._dim is None:
            raise InvalidParameter("constant: dimension unknown until the first measurement")
        return self._dim

    def with_start(self, start: np.ndarray) -> Trajectory:
        return self if not self.needs_start else Constant(np.asarray(start, dtype=float))

    def sample(self, t_s: float) -> Sample:
        if self.value is None:
            raise InvalidParameter("constant: no value yet (give value=[...] or connect "
                                   "the trajectory module's q input)")
        return Sample(pos=self.value, vel=self._zero, acc=self._zero)
