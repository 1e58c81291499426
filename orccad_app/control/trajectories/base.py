"""The trajectory interface: :class:`Trajectory` and its :class:`Sample`."""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass
from typing import Any

import numpy as np

__all__ = ["Sample", "Trajectory", "frozen_array", "position_array", "MAX_POSITION"]

MAX_POSITION = 1e6
"""Largest magnitude of a trajectory position (``q0``, ``goal``, ``start``, ``value``) [rad or
m]: beyond it the set-point, its derivatives or the tracking error's squares leave the finite
numbers (a goal of 1e308 ended ``done`` with an infinite tracking error)."""


@dataclass(frozen=True, slots=True)
class Sample:
    """Desired ``pos``, ``vel`` [/s] and ``acc`` [/s²] at one instant."""

    pos: np.ndarray
    vel: np.ndarray
    acc: np.ndarray


def frozen_array(values: Any) -> np.ndarray:
    array = np.array(values, dtype=float)
    array.setflags(write=False)
    return array


def position_array(values: Any, what: str) -> np.ndarray:
    """``values`` as a frozen array of positions, each finite and within ``MAX_POSITION``."""
    from orccad_app.control.errors import InvalidParameter

    array = frozen_array(values)
    if not np.all(np.isfinite(array)) or np.any(np.abs(array) > MAX_POSITION):
        raise InvalidParameter(f"{what}: positions must be finite and within ±{MAX_POSITION:g} "
                               f"(rad or m), got {values!r}")
    return array


class Trajectory(ABC):
    """A reference signal of dimension :attr:`dim`, immutable."""

    #: kind name, e.g. ``"cosine"``
    name: str = "trajectory"
    #: time [s] after which the trajectory is constant, ``None`` if it never ends
    end_time_s: float | None = None
    #: True while the start position must come from the first measurement
    needs_start: bool = False
    #: the kind and parameters it was made from (set by ``TrajectoryKind.create``), so that a
    #: type-1 update can rebuild it with one parameter changed; ``None``: not retunable
    origin: Any = None

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

    def continuing(self, previous: Trajectory, previous_t_s: float, at_s: float) -> float:
        """The time shift [s] with which this trajectory, replacing ``previous`` (sampled at
        ``previous_t_s``) at task time ``at_s``, keeps its phase; 0 for a kind without phase
        (see :mod:`orccad_app.control.trajectories.retuned`)."""
        return 0.0
