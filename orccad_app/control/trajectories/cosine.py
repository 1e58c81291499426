r"""The cosine reference of RR-1801 eq. 9–10."""

from __future__ import annotations

import math
from typing import Any

from orccad_app.control.errors import InvalidParameter
from orccad_app.control.trajectories.base import (Sample, Trajectory, frozen_array,
                                                  position_array)

MAX_OMEGA = 1e6
"""Largest angular frequency [rad/s] (its square scales the acceleration)."""

__all__ = ["Cosine"]


class Cosine(Trajectory):
    r""":math:`q_d = q_0 (1 + \cos \omega t)` (eq. 9–10); ``q0`` [rad], ``omega`` [rad/s]."""

    name = "cosine"

    def __init__(self, q0: Any, omega: float = math.pi):
        self.q0 = position_array(q0, "cosine q0")
        self.omega = float(omega)
        if not 0 <= self.omega <= MAX_OMEGA:  # NaN fails this test too
            raise InvalidParameter(f"cosine: omega must be in [0, {MAX_OMEGA:g}] rad/s, got "
                                   f"{omega!r}")
        # the velocity and acceleration amplitudes, computed once (same products)
        self._vel_amp = frozen_array(-self.q0 * self.omega)
        self._acc_amp = frozen_array(-self.q0 * self.omega ** 2)

    @property
    def dim(self) -> int:
        return self.q0.size

    def continuing(self, previous: Trajectory, previous_t_s: float, at_s: float) -> float:
        """The shift giving, at ``at_s``, the phase ``omega·t`` the previous cosine had."""
        if not isinstance(previous, Cosine) or self.omega == 0.0:
            return 0.0
        return previous.omega * previous_t_s / self.omega - at_s

    def sample(self, t_s: float) -> Sample:
        phase = self.omega * t_s
        cos = math.cos(phase)
        return Sample(pos=self.q0 * (1.0 + cos), vel=self._vel_amp * math.sin(phase),
                      acc=self._acc_amp * cos)
