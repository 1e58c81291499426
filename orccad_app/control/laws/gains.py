"""Validation of gains and adjusting matrices (coherence checks of a control scheme)."""

from __future__ import annotations

from typing import Any

import numpy as np

from orccad_app.control.errors import DimensionMismatch, InvalidParameter

__all__ = ["gain_matrix", "adjusting_matrix"]


def gain_matrix(owner: str, name: str, value: Any, dim: int, positive: bool = True) -> np.ndarray:
    """Diagonal ``(dim, dim)`` matrix of a scalar or per-component gain.

    Raises naming ``owner``, ``name`` and the value when a component is not > 0 (or < 0
    with ``positive=False``) or the vector has the wrong length.
    """
    values = np.array(value, dtype=float).reshape(-1)
    if values.size == 1:
        values = np.full(dim, values[0])
    if values.size != dim:
        raise DimensionMismatch(f"{owner}: {name} has {values.size} components, "
                                f"expected dim e = {dim}")
    bad = values <= 0 if positive else values < 0
    if np.any(bad) or not np.all(np.isfinite(values)):
        relation = "> 0" if positive else ">= 0"
        shown = value.tolist() if isinstance(value, np.ndarray) else value
        raise InvalidParameter(f"{owner}: {name} must be {relation}, got {shown!r}")
    return np.diag(values)


def adjusting_matrix(owner: str, name: str, value: Any, dim: int) -> np.ndarray:
    """A positive ``(dim, dim)`` matrix from a scalar, a diagonal or a full matrix (G, D).

    Raises on a wrong shape (naming it) or a matrix that is not positive definite.
    """
    array = np.array(value, dtype=float)
    if array.ndim < 2:
        return gain_matrix(owner, name, array, dim)
    if array.shape != (dim, dim):
        raise DimensionMismatch(f"{owner}: {name} must be {dim}×{dim}, got shape "
                                f"{array.shape}")
    eigenvalues = np.linalg.eigvalsh(0.5 * (array + array.T))
    if np.any(eigenvalues <= 0):
        raise InvalidParameter(f"{owner}: {name} must be positive definite, got "
                               f"{array.tolist()} (eigenvalues {np.round(eigenvalues, 6).tolist()})")
    return array
