"""The mission's state as plottable topics: the automaton's state and where it waits, each
Robot-Task's phase, each property's running verdict.

Messages (JSON, each with its JSON Schema below; every one a *state* topic, sent again to a
live client that subscribes late):

- ``/mission/state`` — ``orccad.AutomatonState`` ``{"state", "at", "waiting_at", "status"}``
  at each change of the automaton's state: its number (plottable), the statements it waits
  at (``waiting_at``: ``file:line:col`` each; ``at``: the same as one text for a State
  Transitions panel on ``/mission/state.at``) and the mission's status (``running``,
  ``done``…);
- ``/mission/phase/<Task>`` — ``orccad.Phase`` ``{"value", "phase"}``: the Robot-Task's phase
  (``0`` idle, ``1`` synchronizing, ``2`` measuring, ``3`` active: the highest of its run
  sites) at each change;
- ``/properties/<name>`` — ``orccad.Verdict`` ``{"verdict", "value", "robustness", "unit",
  "samples"}``: the property's verdict on the run so far (``true``/``false``/``undecided``,
  ``value`` 1/-1/0 to plot) and, for a signal property, its robustness when finite (left out
  otherwise: an LTL property, or ``±inf`` when no comparison decides it).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

__all__ = ["VerdictSample", "PHASE_NAMES", "STATE_SCHEMA", "PHASE_SCHEMA", "VERDICT_SCHEMA",
           "state_message", "phase_message", "verdict_message"]

PHASE_NAMES = ("idle", "synchronizing", "measuring", "active")
"""A Robot-Task's phase by number (RR-1801 §3.4.3; ``0``: not running)."""

VERDICTS = {"true": 1, "undecided": 0, "false": -1}
"""A verdict as a number to plot."""


@dataclass(frozen=True)
class VerdictSample:
    """A property's verdict on the run so far.

    :param name: the property (``safe_depth``).
    :param verdict: ``true``, ``false`` or ``undecided``.
    :param robustness: a signal property's robustness (in ``unit``), ``None`` for an LTL one.
    :param unit: the robustness's unit (``[m]``), ``""`` when unknown or mixed.
    :param samples: the instants or samples judged.
    """

    name: str
    verdict: str
    robustness: float | None = None
    unit: str = ""
    samples: int = 0


_STRING = {"type": "string"}
_INTEGER = {"type": "integer"}

STATE_SCHEMA = {
    "title": "orccad.AutomatonState", "type": "object",
    "properties": {"state": {"type": "integer", "minimum": 0}, "at": _STRING,
                   "waiting_at": {"type": "array", "items": _STRING}, "status": _STRING},
    "required": ["state", "at", "waiting_at", "status"]}

PHASE_SCHEMA = {
    "title": "orccad.Phase", "type": "object",
    "properties": {"value": {"type": "integer", "minimum": 0, "maximum": 3},
                   "phase": {"enum": list(PHASE_NAMES)}},
    "required": ["value", "phase"]}

VERDICT_SCHEMA = {
    "title": "orccad.Verdict", "type": "object",
    "properties": {"verdict": {"enum": list(VERDICTS)},
                   "value": {"type": "integer", "minimum": -1, "maximum": 1},
                   "robustness": {"type": "number"}, "unit": _STRING,
                   "samples": {"type": "integer", "minimum": 0}},
    "required": ["verdict", "value", "unit", "samples"]}


def state_message(state: int, waiting_at: Sequence[Any], status: str) -> dict[str, Any]:
    """``/mission/state``'s message: the state, the statements it waits at, the status."""
    at = list(dict.fromkeys(str(location) for location in waiting_at))  # unique, in order
    return {"state": state, "at": ", ".join(at), "waiting_at": at, "status": status}


def phase_message(phase: int) -> dict[str, Any]:
    """``/mission/phase/<Task>``'s message for ``phase`` (0 to 3)."""
    return {"value": phase, "phase": PHASE_NAMES[phase]}


def verdict_message(sample: VerdictSample) -> dict[str, Any]:
    """``/properties/<name>``'s message."""
    message: dict[str, Any] = {"verdict": sample.verdict, "value": VERDICTS[sample.verdict],
                               "unit": sample.unit, "samples": sample.samples}
    if sample.robustness is not None and math.isfinite(sample.robustness):
        message["robustness"] = sample.robustness
    return message
