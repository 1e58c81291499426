"""What one evaluation of a control law returns (shared by the general and the lean path)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["LawOutput"]


@dataclass(frozen=True, slots=True)
class LawOutput:
    """One evaluation: ``tau`` [N·m] after the actuator constraint, ``tau_unsat`` before
    it, the ``saturated`` joints mask and the task error ``e``."""

    tau: np.ndarray
    tau_unsat: np.ndarray
    saturated: np.ndarray
    e: np.ndarray
