"""Derivative estimation for inputs that are not connected (velocity from positions)."""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["BackwardDifference"]


class BackwardDifference:
    """Backward-difference derivative of a sampled vector signal [unit/s].

    With ``on_change=False`` every call is a new sample (a sensor read at each job: an
    unchanged value means zero velocity). With ``on_change=True`` only a changed value is
    a new sample and the derivative is held in between (a slower producer whose last value
    is read again: repeated values are stale, not a stop).
    """

    def __init__(self, on_change: bool = False):
        self.on_change = on_change
        self.reset()

    def reset(self) -> None:
        """Forget past samples; the next derivative is zero."""
        self._t: float | None = None
        self._value: np.ndarray | None = None
        self._listed: Any = None
        """``_value.tolist()``: compared with a new sample's list (cheaper than
        ``np.array_equal`` for a few components; NaN differs from itself in both)."""
        self._derivative: np.ndarray | None = None

    def update(self, t_s: float, value: np.ndarray) -> np.ndarray:
        """Add the sample ``value`` at ``t_s`` [s]; return the current derivative."""
        value = np.asarray(value, dtype=float)
        if self._value is None or self._t is None:
            self._t, self._value = t_s, value.copy()
            self._listed = value.tolist() if value.ndim else [value.tolist()]
            self._derivative = np.zeros_like(value)
            return self._derivative.copy()
        listed = value.tolist() if value.ndim else [value.tolist()]
        if self.on_change and value.shape == self._value.shape and listed == self._listed:
            return self._derivative.copy()
        dt = t_s - self._t
        if dt > 0.0:
            self._derivative = (value - self._value) / dt
            self._t, self._value, self._listed = t_s, value.copy(), listed
        return self._derivative.copy()
