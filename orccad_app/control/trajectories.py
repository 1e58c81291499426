r"""Reference trajectories: desired position, velocity and acceleration over time.

- :class:`Cosine` — RR-1801 eq. 9–10: :math:`q_d = q_0 (1 + \cos \omega t)`,
  :math:`\dot q_d = -q_0 \omega \sin \omega t` (the paper uses :math:`\omega = \pi`).
- :class:`MinimumJerk` — point to point in ``duration`` [s] with zero velocity and
  acceleration at both ends: :math:`s(\tau) = 10\tau^3 - 15\tau^4 + 6\tau^5`.
- :class:`Constant` — hold a position.

Time ``t_s`` [s] is measured from the start of the trajectory. Units follow the task
function: [rad] for joint tracking, [m] for Cartesian tracking. A trajectory whose start
is not given (``needs_start``) is completed with :meth:`Trajectory.with_start` from the
first measurement (the ``trajectory`` module's ``q`` input).
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from dataclasses import dataclass
from typing import Any

import numpy as np

from orccad_app.control.errors import DimensionMismatch, InvalidParameter
from orccad_app.control.params import REQUIRED, ParamSpec

__all__ = [
    "Sample",
    "Trajectory",
    "Cosine",
    "MinimumJerk",
    "Constant",
    "COSINE",
    "MINIMUM_JERK",
    "CONSTANT",
]


@dataclass(frozen=True)
class Sample:
    """Desired ``pos``, ``vel`` [/s] and ``acc`` [/s²] at one instant."""

    pos: np.ndarray
    vel: np.ndarray
    acc: np.ndarray


def _frozen(values: Any) -> np.ndarray:
    array = np.array(values, dtype=float)
    array.setflags(write=False)
    return array


class Trajectory(ABC):
    """A reference signal of dimension :attr:`dim`, immutable."""

    #: kind name, e.g. ``"cosine"``
    name: str = "trajectory"
    #: time [s] after which the trajectory is constant, ``None`` if it never ends
    end_time_s: float | None = None
    #: True while the start position must come from the first measurement
    needs_start: bool = False

    @property
    @abstractmethod
    def dim(self) -> int:
        """Number of components."""

    @abstractmethod
    def sample(self, t_s: float) -> Sample:
        """Desired position, velocity and acceleration at ``t_s`` [s] from the start."""

    def final(self) -> np.ndarray | None:
        """Final position when the trajectory ends, else ``None``."""
        if self.end_time_s is None or self.needs_start:
            return None
        return self.sample(self.end_time_s).pos

    def with_start(self, start: np.ndarray) -> Trajectory:
        """This trajectory starting from the measured ``start`` (no-op if not needed)."""
        return self


class Cosine(Trajectory):
    r""":math:`q_d = q_0 (1 + \cos \omega t)` (eq. 9–10); ``q0`` [rad], ``omega`` [rad/s]."""

    name = "cosine"

    def __init__(self, q0: Any, omega: float = math.pi):
        self.q0 = _frozen(q0)
        self.omega = float(omega)

    @property
    def dim(self) -> int:
        return self.q0.size

    def sample(self, t_s: float) -> Sample:
        phase = self.omega * t_s
        return Sample(pos=self.q0 * (1.0 + math.cos(phase)),
                      vel=-self.q0 * self.omega * math.sin(phase),
                      acc=-self.q0 * self.omega ** 2 * math.cos(phase))


class MinimumJerk(Trajectory):
    """From ``start`` to ``goal`` in ``duration`` [s], minimum jerk; then holds ``goal``.

    ``start=None`` takes the start from the first measurement (see :meth:`with_start`).
    """

    name = "min_jerk"

    def __init__(self, goal: Any, duration: float, start: Any = None):
        if not duration > 0:
            raise InvalidParameter(f"min_jerk: duration must be > 0, got {duration!r}")
        self.goal = _frozen(goal)
        self.duration = float(duration)
        self.start = None if start is None else _frozen(start)
        if self.start is not None and self.start.shape != self.goal.shape:
            raise DimensionMismatch(f"min_jerk: start has {self.start.size} components "
                                    f"but goal has {self.goal.size}")
        self.end_time_s = self.duration
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
        delta = self.goal - self.start
        return Sample(pos=self.start + s * delta, vel=ds * delta, acc=dds * delta)


class Constant(Trajectory):
    """Hold ``value``; ``value=None`` holds the first measured position."""

    name = "constant"
    end_time_s = 0.0

    def __init__(self, value: Any = None, dim: int | None = None):
        self.value = None if value is None else _frozen(value)
        self._dim = self.value.size if self.value is not None else dim
        self.needs_start = self.value is None

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
        zero = np.zeros_like(self.value)
        return Sample(pos=self.value, vel=zero, acc=zero)
