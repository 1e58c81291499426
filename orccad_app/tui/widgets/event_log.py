"""The run's log of signals, exceptions, Robot-Task starts and ends, with a filter."""

from __future__ import annotations

from rich.text import Text
from textual import on
from textual.app import ComposeResult
from textual.containers import Vertical
from textual.widgets import Input, RichLog

from orccad_app.tui.live import LogEntry

__all__ = ["EventLog"]

_STYLES = {"exception": "bold red", "miss": "red", "input": "bold cyan",
           "fault": "bold magenta", "output": "green", "task": "", "param": "yellow",
           "status": "bold"}


class EventLog(Vertical):
    """Every :class:`~orccad_app.tui.live.LogEntry`; those containing the filter's text
    (case-insensitive) are shown."""

    DEFAULT_CSS = """
    EventLog { height: 1fr; }
    EventLog Input { height: 1; }
    EventLog RichLog { height: 1fr; }
    """

    MAX_LINES = 5000
    """Lines kept on screen (every entry is kept for the filter)."""

    def __init__(self, **kwargs) -> None:
        super().__init__(**kwargs)
        self.entries: list[LogEntry] = []
        self._filter = ""

    def compose(self) -> ComposeResult:
        yield Input(placeholder="filter the log (e.g. exception, Stop, TrackPID)",
                    id="log-filter", compact=True)
        yield RichLog(id="log-lines", wrap=True, markup=False, min_width=20,
                      max_lines=self.MAX_LINES)

    def add(self, entries: list[LogEntry]) -> None:
        self.entries.extend(entries)
        lines = self.query_one(RichLog)
        for entry in entries:
            if self._matches(entry):
                lines.write(Text(entry.format(), style=_STYLES.get(entry.kind, "")))

    def shown(self) -> list[LogEntry]:
        """The entries the filter lets through."""
        return [entry for entry in self.entries if self._matches(entry)]

    def _matches(self, entry: LogEntry) -> bool:
        return not self._filter or self._filter in entry.format().lower()

    @on(Input.Changed, "#log-filter")
    def _filter_changed(self, event: Input.Changed) -> None:
        self._filter = event.value.strip().lower()
        lines = self.query_one(RichLog)
        lines.clear()
        for entry in self.shown()[-self.MAX_LINES:]:
            lines.write(Text(entry.format(), style=_STYLES.get(entry.kind, "")))
