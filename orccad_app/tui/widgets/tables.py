"""Small tables of the run screen: running Robot-Tasks, processors and deadline misses."""

from __future__ import annotations

from textual.widgets import DataTable

from orccad_app.tui.live import PHASES

__all__ = ["TaskTable", "LoadTable", "TcsTable"]


class TaskTable(DataTable):
    """The Robot-Tasks running now and the phase of each one's RTA."""

    DEFAULT_CSS = "TaskTable { height: auto; max-height: 8; }"

    def on_mount(self) -> None:
        self.cursor_type = "none"
        self.add_columns("task", "site", "phase")

    def show(self, tasks: list[tuple[str, int, int]]) -> None:
        self.clear()
        for task, site, phase in tasks:
            self.add_row(task, str(site), f"{phase} {PHASES.get(phase, '')}")
        if not tasks:
            self.add_row("(none)", "", "")


class LoadTable(DataTable):
    """Per processor, its load over the last update; per module, its deadline misses."""

    DEFAULT_CSS = "LoadTable { height: auto; max-height: 10; }"

    def on_mount(self) -> None:
        self.cursor_type = "none"
        self.add_columns("cpu / module", "load", "miss")

    def show(self, loads: dict[str, float], misses: dict[str, int]) -> None:
        self.clear()
        for processor, load in sorted(loads.items()):
            self.add_row(processor, f"{load:.1%}", "")
        for module, count in sorted(misses.items()):
            self.add_row(f"  {module}", "", str(count))
        if not misses:
            self.add_row("deadline misses", "", "0")


class TcsTable(DataTable):
    """The TCS: every Module-Task with processor, period, WCET, priority, whether its task
    runs now and its deadline misses; then each processor's load."""

    DEFAULT_CSS = "TcsTable { height: 1fr; }"

    def on_mount(self) -> None:
        self.cursor_type = "row"
        self.add_columns("Module-Task", "cpu", "T ms", "C ms", "prio", "active/load", "misses")

    def show(self, rows: list[tuple[str, ...]]) -> None:
        self.clear()
        for row in rows:
            self.add_row(*row)
