"""The label of a sub-mission's region (``run mission M``) in a compiled mission's states.

Like the Robot-Task labels (:mod:`orccad_app.robottask.labels`), it marks an
:class:`~orccad_app.reactive.ir.Mark` region, so every state says which sub-missions it is in:
``Homing#2 (missions/lib/homing.orc:8) inside missions/arm_recovery.orc:54`` is the second
instance of mission ``Homing`` (declared at ``homing.orc:8``), run by the ``run mission``
statement at ``arm_recovery.orc:54``.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Iterable

from orccad_app.diagnostics import NOWHERE, SourceLocation

__all__ = ["MissionLabel", "InMission", "sub_mission_labels", "in_missions"]


@dataclass(frozen=True, order=True)
class MissionLabel:
    """The region of one inlined ``run mission M``.

    :param mission: the sub-mission's name ``M``.
    :param instance: which instance of ``M`` (from 1, in lowering order).
    :param defined: where ``M`` is declared (its file may be an imported one).
    :param call: the ``run mission`` statement.
    """

    mission: str
    instance: int
    defined: SourceLocation = field(default=NOWHERE, compare=False)
    call: SourceLocation = field(default=NOWHERE, compare=False)

    @property
    def name(self) -> str:
        """``M#n``."""
        return f"{self.mission}#{self.instance}"

    def text(self) -> str:
        """``M#n (file:line) inside file:line`` (declaration, then call site)."""
        if self.defined.line <= 0:
            return self.name
        where = f"{self.name} ({self.defined.file}:{self.defined.line})"
        if self.call.line <= 0:
            return where
        return f"{where} inside {self.call.file}:{self.call.line}"

    def owns(self, loc: SourceLocation) -> bool:
        """Whether a waiting location is the sub-mission's own: in its file when that is not
        the caller's, else inside the mission's declaration."""
        if loc.file != self.defined.file:
            return False
        if self.defined.file != self.call.file:
            return True
        end = self.defined.end_line or self.defined.line
        return self.defined.line <= loc.line <= end

    def statements(self, waiting: Iterable[SourceLocation]) -> list[SourceLocation]:
        """The locations of ``waiting`` that are the sub-mission's own, sorted, unique."""
        return sorted({loc for loc in waiting if self.owns(loc)},
                      key=lambda loc: (loc.line, loc.col))


def sub_mission_labels(labels: Iterable[object]) -> list[MissionLabel]:
    """The sub-mission labels among a state's ``labels``, outermost (earliest call) first."""
    return sorted((label for label in labels if isinstance(label, MissionLabel)),
                  key=lambda label: (label.call.file, label.call.line, label.call.col,
                                     label.mission, label.instance))


@dataclass(frozen=True)
class InMission:
    """A state inside a sub-mission instance: its label and the sub-mission's own statements
    the state waits at (:meth:`MissionLabel.statements`)."""

    label: MissionLabel
    at: tuple[SourceLocation, ...] = ()

    def text(self) -> str:
        """``Homing#2 (lib/homing.orc:8) inside arm_recovery.orc:54, at lib/homing.orc:26``."""
        if not self.at:
            return self.label.text()
        lines = ", ".join(dict.fromkeys(str(loc.line) for loc in self.at))
        return f"{self.label.text()}, at {self.at[0].file}:{lines}"

    def to_dict(self) -> dict[str, object]:
        """JSON-ready: the label's fields, its text and the statements."""
        label = self.label
        return {"mission": label.mission, "instance": label.instance, "text": self.text(),
                "defined_at": str(label.defined), "called_at": str(label.call),
                "waiting_at": [str(loc) for loc in self.at]}


def in_missions(labels: Iterable[object],
                waiting: Iterable[SourceLocation]) -> tuple[InMission, ...]:
    """The sub-mission instances of a state (its ``labels``, outermost first) with the
    statements of each the state waits at (``waiting``)."""
    waiting = tuple(waiting)
    return tuple(InMission(label, tuple(label.statements(waiting)))
                 for label in sub_mission_labels(labels))
