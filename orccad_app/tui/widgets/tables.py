"""Small tables of the run screen: running Robot-Tasks, processors and deadline misses."""

from __future__ import annotations

from textual.widgets import DataTable

from orccad_app.robottask.labels import Phase

__all__ = ["TaskTable", "LoadTable", "TcsTable"]


class _Rows(DataTable):
    """A table redrawn only when its rows change (a live run updates it every frame)."""

    _shown: list[tuple[str, ...]] | None = None

    def set_rows(self, rows: list[tuple[str, ...]]) -> None:
        if rows == self._shown:
            return
        self._shown = rows
        self.clear()
        for row in rows:
            self.add_row(*row)


class TaskTable(_Rows):
    """The Robot-Tasks running now and the phase of each one's RTA."""

    DEFAULT_CSS = "TaskTable { height: auto; max-height: 8; }"

    def on_mount(self) -> None:
        self.cursor_type = "none"
        self.add_columns("task", "site", "phase")

    def show(self, tasks: list[tuple[str, int, int]]) -> None:
        self.set_rows([(task, str(site), f"{phase} {Phase(phase).word}")
                       for task, site, phase in tasks] or [("(none)", "", "")])


class LoadTable(_Rows):
    """Per processor, its load over the last update; per module, its deadline misses."""

    DEFAULT_CSS = "LoadTable { height: auto; max-height: 10; }"

    def on_mount(self) -> None:
        self.cursor_type = "none"
        self.add_columns("cpu / module", "load", "miss")

    def show(self, loads: dict[str, float], misses: dict[str, int]) -> None:
        rows: list[tuple[str, ...]] = [(processor, f"{load:.1%}", "")
                                       for processor, load in sorted(loads.items())]
        rows += [(f"  {module}", "", str(count)) for module, count in sorted(misses.items())]
        self.set_rows(rows + ([] if misses else [("deadline misses", "", "0")]))


class TcsTable(_Rows):
    """The TCS: every Module-Task with processor, period, WCET, priority, whether its task
    runs now and its deadline misses; then each processor's load."""

    DEFAULT_CSS = "TcsTable { height: 1fr; }"

    def on_mount(self) -> None:
        self.cursor_type = "row"
        self.add_columns("Module-Task", "cpu", "T ms", "C ms", "prio", "active/load", "misses")

    def show(self, rows: list[tuple[str, ...]]) -> None:
        self.set_rows(rows)
