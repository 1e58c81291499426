"""The labels of a compiled mission's states: which Robot-Task instance runs, in which phase.

The RTA of each ``run`` site is a marked region (:class:`~orccad_app.reactive.ir.Mark`) whose
label is an :class:`RtLabel`; each of its three phases is a nested region labelled
:class:`PhaseLabel`. The compiled automaton lists, for every state, the labels of the regions
it is in, so ``active(X)`` and "X is in phase 2" are properties of states, read by the
checker (:mod:`orccad_app.verify.model`) and the mission run (:mod:`orccad_app.mission.run`).
"""

from __future__ import annotations

import enum
from dataclasses import dataclass

__all__ = ["Phase", "RtLabel", "PhaseLabel"]


class Phase(enum.IntEnum):
    """The phases of a Robot-Task's behaviour automaton (RR-1801 §3.4.3), in order.

    A running instance is in exactly one of the three phases; one that is not running is
    :attr:`IDLE` (``0`` in traces and topics).
    """

    IDLE = 0
    """Not running (not started yet, or ended, raised or killed)."""
    SYNCHRONIZING = 1
    """Waiting for the synchronization pre-conditions (mission signals); no module runs."""
    MEASURING = 2
    """Waiting for the measurement pre-conditions; only the measuring modules (the observers
    serving them) run."""
    ACTIVE = 3
    """The control scheme runs: every module; exceptions and post-conditions are watched."""

    @property
    def word(self) -> str:
        """One word for people: ``idle``, ``waiting``, ``measuring``, ``running``."""
        return _PHASE_WORDS[self]


_PHASE_WORDS = {Phase.IDLE: "idle", Phase.SYNCHRONIZING: "waiting",
                Phase.MEASURING: "measuring", Phase.ACTIVE: "running"}


@dataclass(frozen=True, order=True)
class RtLabel:
    """The region of the Robot-Task instance at one ``run`` site.

    :param task: the Robot-Task's name.
    :param site: the run site's number (source order in the mission, from 0).
    """

    task: str
    site: int


@dataclass(frozen=True, order=True)
class PhaseLabel:
    """One phase region inside an :class:`RtLabel` region.

    :param task: the Robot-Task's name.
    :param site: the run site's number.
    :param phase: which phase.
    """

    task: str
    site: int
    phase: Phase
