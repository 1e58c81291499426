"""Errors raised by the control library.

Every error here is an :class:`~orccad_app.diagnostics.OrccadError` (exit status 2 at the
CLI): a control scheme that is badly specified is bad input, never a bug. Messages name the
offending parameter and value, e.g. ``pid: kp must be > 0, got -1.0``.
"""

from __future__ import annotations

from orccad_app.diagnostics import OrccadError

__all__ = ["ControlError", "InvalidParameter", "DimensionMismatch"]


class ControlError(OrccadError):
    """A control scheme, robot model or module is incoherent."""


class InvalidParameter(ControlError):
    """A parameter has the wrong type, is out of range, is unknown or is missing."""


class DimensionMismatch(ControlError):
    """Sizes do not agree: ``dim e != dim q``, a matrix of the wrong shape, a short vector."""
