"""Messages of the terminal UI (posted from the executive's worker thread or by widgets)."""

from __future__ import annotations

from typing import Any

from textual.message import Message

from orccad_app.tui.live import LiveUpdate

__all__ = ["RunUpdated", "RunFinished", "RunFailed", "InputRequested", "FileChosen",
           "CheckDone"]


class RunUpdated(Message):
    """What the live run did since the previous update."""

    bubble = False  # addressed to the screen that runs the work

    def __init__(self, update: LiveUpdate) -> None:
        super().__init__()
        self.update = update


class RunFinished(Message):
    """The run ended: its ``RunResult`` and ``orccad run``'s text report."""

    bubble = False  # addressed to the screen that runs the work

    def __init__(self, result: Any, report: str) -> None:
        super().__init__()
        self.result = result
        self.report = report


class RunFailed(Message):
    """The run could not be built or raised: the message shown to the user."""

    bubble = False  # addressed to the screen that runs the work

    def __init__(self, message: str) -> None:
        super().__init__()
        self.message = message


class InputRequested(Message):
    """The user asked to raise the automaton input ``name`` (with ``value`` when valued) —
    once, or held at every instant (``hold``), or to stop holding it (``release``) — or to
    inject the plant fault ``name`` (``ROBOT.FAULT``) with ``value`` when ``fault``."""

    def __init__(self, name: str, value: Any = None, fault: bool = False, *,
                 hold: bool = False, release: bool = False) -> None:
        super().__init__()
        self.name = name
        self.value = value
        self.fault = fault
        self.hold = hold
        self.release = release


class FileChosen(Message):
    """A file was selected in the mission browser's list."""

    def __init__(self, path: str) -> None:
        super().__init__()
        self.path = path


class CheckDone(Message):
    """``orccad check`` finished on a mission: the text of its verdicts."""

    bubble = False  # addressed to the screen that runs the work

    def __init__(self, mission: str, text: str, holds: bool, report: Any = None) -> None:
        super().__init__()
        self.mission = mission
        self.text = text
        self.holds = holds
        self.report = report
        """The ``MissionReport`` (``None`` when the check could not run)."""
