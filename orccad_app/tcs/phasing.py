"""Release phasing between two Module-Tasks: how far the next release of one can be from a
given instant of the other, exactly, without enumerating a hyperperiod.

Two periodic Module-Tasks activated at the same instant release at ``o_A + i·T_A`` and
``o_B + j·T_B`` (``o`` the offsets). For a release ``r`` of A and a delay ``x >= 0``, the
distance from ``r + x`` to the next release of B is ``(o_B - o_A - x - i·T_A) mod T_B``. As
``i`` runs, ``i·T_A mod T_B`` takes every multiple of ``G = gcd(T_A, T_B)`` below ``T_B``, so
the distances are exactly the values congruent to ``o_B - o_A - x`` modulo ``G`` in
``[0, T_B)``; their maximum is

.. math::

    T_B - G + ((o_B - o_A - x) \\bmod G).

("after" instead of "at or after": :math:`T_B - G + ((o_B - o_A - x - 1) \\bmod G) + 1`.)
This is exact for any periods, however absurd their hyperperiod (periods of 1 ms and
1000001 ns have ``G`` = 1 ns: the phase drifts through every value, and the bound is
``T_B - 1`` ns, not the 0 a "nearly equal periods" reasoning would give).

The phase is used only when both start together (same activation instant and offset), so
that every release of one has a release of the other at or before it. When it is not known —
the two Module-Tasks are not activated together (a measuring observer starts in phase 2, the
others in phase 3), their offsets differ, or A is sporadic — the bound is ``T_B``.
When B is sporadic there is no bound (``None``): its next release may never come.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum
from math import gcd

__all__ = ["Activation", "Phase", "next_release_gap_ns", "previous_release_gap_ns",
           "releases_in_window", "PHASE_ENUMERATION_BUDGET"]

PHASE_ENUMERATION_BUDGET = 4096
"""Largest number of relative phases :func:`releases_in_window` enumerates; beyond, it uses
the phase-free count."""


class Activation(str, Enum):
    """How a Module-Task's jobs are released."""

    PERIODIC = "periodic"
    """Every ``period_ns`` from its activation (+ offset)."""
    SPORADIC = "sporadic"
    """On an event (an interrupt), at least ``min_interarrival_ns`` apart; no known phase."""


@dataclass(frozen=True, slots=True)
class Phase:
    """What the analysis knows of one Module-Task's releases.

    :param period_ns: the period, or the minimum inter-arrival time of a sporadic one [ns].
    :param offset_ns: the first release after activation [ns].
    :param activation: periodic or sporadic.
    :param group: the activation stage: Module-Tasks of the same stage are activated at the
        same instant, those of a later stage later (a Robot-Task's measuring observers start in
        phase 2, its other modules in phase 3), and all stop together; ``None`` when its
        activation is tied to no other's.
    """

    period_ns: int
    offset_ns: int = 0
    activation: Activation = Activation.PERIODIC
    group: int | None = 0

    def locked_with(self, other: Phase) -> bool:
        """Whether the two release sequences have a known relative phase."""
        return (self.activation is Activation.PERIODIC
                and other.activation is Activation.PERIODIC
                and self.group is not None and self.group == other.group
                and self.offset_ns == other.offset_ns)


    def starts_after(self, other: Phase) -> bool:
        """Whether this Module-Task may be inactive while ``other`` runs (a later stage)."""
        return self.group is not None and other.group is not None and self.group > other.group


def next_release_gap_ns(a: Phase, b: Phase, delay_ns: int = 0,
                        strict: bool = False) -> int | None:
    """The longest time from ``delay_ns`` after a release of ``a`` to the next release of
    ``b`` at or after that instant (``strict``: after it) [ns]; ``None`` when unbounded
    (``b`` sporadic)."""
    if b.activation is Activation.SPORADIC:
        return None
    if not a.locked_with(b):
        return b.period_ns
    g = gcd(a.period_ns, b.period_ns)
    if strict:
        return b.period_ns - g + (b.offset_ns - a.offset_ns - delay_ns - 1) % g + 1
    return b.period_ns - g + (b.offset_ns - a.offset_ns - delay_ns) % g


def previous_release_gap_ns(a: Phase, b: Phase) -> int | None:
    """The longest time from the latest release of ``b`` at or before a release of ``a`` to
    that release [ns]; ``None`` when unbounded (``b`` sporadic)."""
    if b.activation is Activation.SPORADIC:
        return None
    if not a.locked_with(b):
        return b.period_ns
    g = gcd(a.period_ns, b.period_ns)
    return b.period_ns - g + (a.offset_ns - b.offset_ns) % g


def releases_in_window(a: Phase, b: Phase, before_ns: int, after_ns: int) -> int:
    """The most releases of ``b`` in ``(r - before_ns, r + after_ns]`` for a release ``r`` of
    ``a`` (``before_ns <= T_B``): over the relative phases the gcd allows when both start
    together, else over any phase."""
    period = b.period_ns
    free = (before_ns + after_ns) // period + 1
    if not a.locked_with(b):
        return free
    g = gcd(a.period_ns, period)
    if period // g > PHASE_ENUMERATION_BUDGET:
        return free
    best = 0
    for delta in range((b.offset_ns - a.offset_ns) % g, period, g):
        ahead = (after_ns - delta) // period + 1 if after_ns >= delta else 0
        behind = 1 if delta - period > -before_ns else 0
        best = max(best, ahead + behind)
    return best
