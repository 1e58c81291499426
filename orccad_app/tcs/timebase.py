"""The executive's timebase: integer nanoseconds.

Every duration and instant in the TCS and the executive is an ``int`` count of nanoseconds
(``period_ns``, ``wcet_ns``, ``until_ns``). Integers keep event ordering exact and runs
reproducible bit for bit; floats appear only where physics or control code wants seconds.
"""

from __future__ import annotations

__all__ = ["NS_PER_S", "ns", "us", "ms", "s", "to_seconds"]

NS_PER_S = 1_000_000_000


def ns(value: float) -> int:
    """``value`` nanoseconds as an ``int`` [ns]."""
    return int(round(value))


def us(value: float) -> int:
    """``value`` microseconds in [ns]."""
    return int(round(value * 1_000))


def ms(value: float) -> int:
    """``value`` milliseconds in [ns]."""
    return int(round(value * 1_000_000))


def s(value: float) -> int:
    """``value`` seconds in [ns]."""
    return int(round(value * NS_PER_S))


def to_seconds(time_ns: int) -> float:
    """An instant or duration in [ns] as [s]."""
    return time_ns / NS_PER_S
