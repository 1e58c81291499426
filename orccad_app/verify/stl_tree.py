"""The tree of a signal property as evaluated on runs: signal arithmetic under comparisons,
boolean and temporal operators, time bounds in nanoseconds.

Built from a parsed property by :func:`orccad_app.verify.stl.translate`; evaluated by
:mod:`orccad_app.verify.stl_eval` (linear in the run) and written in rtamt's language by
:mod:`orccad_app.verify.stl_rtamt` (the reference the evaluator is tested against).
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum
from typing import Union

__all__ = ["Var", "Const", "Arith", "Call", "SignalTerm", "Margin", "Event", "Not", "Junction",
           "Shift", "Window", "Until", "Node", "Direction", "UndefinedRobustness"]


class UndefinedRobustness(Exception):
    """The property has no robustness on this run (``reason`` says why): a division by zero,
    the square root of a negative value, a value that is not a number on some sample, or an
    overflow of its arithmetic to ±inf. The run's verdict is then *undecided*; the run itself
    goes on."""

    def __init__(self, reason: str) -> None:
        super().__init__(reason)
        self.reason = reason


class Direction(str, Enum):
    """Where a temporal operator looks: the samples after the current one, or before it."""

    FUTURE = "future"
    PAST = "past"


# --------------------------------------------------------------------- signal arithmetic

@dataclass(frozen=True)
class Var:
    """A sampled variable: a port component (``s0``) or an event atom (``e0``, ±inf)."""

    name: str


@dataclass(frozen=True)
class Const:
    value: float


@dataclass(frozen=True)
class Arith:
    """``left op right``; op in ``+ - * /`` (a division by zero on any sample: undefined)."""

    op: str
    left: "SignalTerm"
    right: "SignalTerm"


@dataclass(frozen=True)
class Call:
    """``abs(arg)`` or ``sqrt(arg)`` (a negative argument on any sample: undefined)."""

    func: str
    arg: "SignalTerm"


SignalTerm = Union[Var, Const, Arith, Call]


# --------------------------------------------------------------------------- formulas

@dataclass(frozen=True)
class Margin:
    """A comparison's robustness: ``right - left`` for ``<``, ``<=``; ``left - right`` for
    ``>``, ``>=``."""

    op: str
    left: SignalTerm
    right: SignalTerm


@dataclass(frozen=True)
class Event:
    """An event atom: its variable's samples are ``+inf`` when the event holds, ``-inf``
    when not (no comparison: no overflow)."""

    name: str


@dataclass(frozen=True)
class Not:
    operand: "Node"


@dataclass(frozen=True)
class Junction:
    """``and`` (min), ``or`` (max), ``implies`` (max of the negated left and the right)."""

    op: str
    left: "Node"
    right: "Node"


@dataclass(frozen=True)
class Shift:
    """``next`` (FUTURE; ``+inf`` at the last sample) or ``previously`` (PAST; ``+inf`` at the
    first)."""

    direction: Direction
    operand: "Node"


@dataclass(frozen=True)
class Window:
    """``always`` / ``eventually`` (FUTURE), ``historically`` / ``once`` (PAST): the minimum
    (``always``, ``historically``) or maximum of the operand over ``[low_ns, high_ns]`` after
    (before) the sample; unbounded (``high_ns`` ``None``, ``low_ns`` 0) to the end (start) of
    the run. An empty window gives the neutral element (``+inf`` for min, ``-inf`` for max)."""

    op: str
    direction: Direction
    operand: "Node"
    low_ns: int = 0
    high_ns: int | None = None

    @property
    def minimum(self) -> bool:
        return self.op in ("always", "historically")


@dataclass(frozen=True)
class Until:
    """``left until[low, high] right`` (FUTURE) or ``left since[low, high] right`` (PAST);
    unbounded when ``high_ns`` is ``None``."""

    direction: Direction
    left: "Node"
    right: "Node"
    low_ns: int = 0
    high_ns: int | None = None


Node = Union[Margin, Event, Not, Junction, Shift, Window, Until]
