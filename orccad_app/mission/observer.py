"""Observing a mission run: the mission-level callbacks, besides the executive's.

An observer passed to :class:`~orccad_app.mission.run.MissionRun` gets the executive's
callbacks (:class:`~orccad_app.executive.observer.Observer`) and, when it defines them, the
mission's own (:data:`MISSION_HOOKS`, documented on :class:`MissionObserver`): traces and the
TUI observe a run this way, without reaching into it.
"""

from __future__ import annotations

from orccad_app.executive.observer import Observer
from orccad_app.mission.result import ExceptionRecord
from orccad_app.robottask.labels import Phase

__all__ = ["MISSION_HOOKS", "MissionObserver"]

MISSION_HOOKS = ("on_reaction", "on_task_start", "on_task_end", "on_exception", "on_state",
                 "on_warning")
"""Mission-level callbacks an observer may define besides the executive's."""


class MissionObserver(Observer):
    """The executive's callbacks and the mission's; every default does nothing."""

    def on_reaction(self, t_ns: int, inputs: tuple[str, ...], outputs: tuple[str, ...],
                    status: str) -> None:
        """The automaton reacted at ``t_ns`` to ``inputs``, emitting ``outputs``; ``status``
        is the mission's (``running``, ``done``, ``failed``, ``aborted``)."""

    def on_task_start(self, t_ns: int, task: str, site: int, args: dict) -> None:
        """Robot-Task ``task`` started at run site ``site`` with ``args`` (parameter ->
        actual value: run-time arguments evaluated, defaults filled in, vectors as lists)."""

    def on_task_end(self, t_ns: int, task: str, site: int, outcome: str) -> None:
        """Robot-Task ``task`` of site ``site`` ended with ``outcome`` (``good_end``, the
        exception that ended it, or ``killed``)."""

    def on_exception(self, record: ExceptionRecord) -> None:
        """An exception was raised (or a type-1 adjustment applied)."""

    def on_state(self, t_ns: int, state: int, phases: dict[int, Phase]) -> None:
        """The automaton entered ``state`` at ``t_ns`` (after the reaction's task starts and
        ends); ``phases`` maps the run site of every running Robot-Task to its phase."""

    def on_warning(self, t_ns: int, source: str, message: str) -> None:
        """The run warns about itself at ``t_ns``: something its records miss (``source``:
        who says it, e.g. ``sil``); a trace's log shows it."""
