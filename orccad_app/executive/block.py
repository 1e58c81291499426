"""The value a channel returns from a read that blocks (:data:`BLOCK`)."""

from __future__ import annotations

__all__ = ["BLOCK"]


class _Blocked:
    """The type of :data:`BLOCK`."""

    def __repr__(self) -> str:
        return "BLOCK"


BLOCK = _Blocked()
"""Returned by ``Channel.read(job)`` when the protocol blocks the reading job."""
