"""The final report of a run (``orccad run``'s text) and the trace export."""

from __future__ import annotations

from textual import on
from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Horizontal, VerticalScroll
from textual.screen import Screen
from textual.widgets import Button, Footer, Header, Input, Static

from orccad_app.tui.session import LiveSession

__all__ = ["ReportScreen"]


class ReportScreen(Screen):
    """Shows the report; ``e`` writes the trace to the path typed (``.csv`` or ``.mcap``)."""

    AUTO_FOCUS = "#report-body"

    BINDINGS = [
        Binding("e", "export", "Export trace"),
        Binding("escape", "app.pop_screen", "Back to the run"),
        Binding("q", "app.quit", "Quit"),
    ]

    def __init__(self, session: LiveSession, report: str) -> None:
        super().__init__()
        self.session = session
        self.report = report

    def compose(self) -> ComposeResult:
        yield Header()
        with VerticalScroll(id="report-body"):
            yield Static(self.report, id="report-text")
        with Horizontal(id="export-bar"):
            yield Input(f"{self.session.mission}-trace.mcap", id="export-path")
            yield Button("Export trace", id="export-button", variant="primary")
        yield Footer()

    def on_mount(self) -> None:
        self.title = f"ORCCAD — report {self.session.mission}"
        self.sub_title = self.session.result.status if self.session.result else ""

    @on(Button.Pressed, "#export-button")
    @on(Input.Submitted, "#export-path")
    def action_export(self) -> None:
        path = self.query_one("#export-path", Input).value.strip()
        try:
            self.session.export(path)
        except Exception as error:  # a bad path or extension: tell, do not crash
            self.notify(f"export failed: {error}", severity="error")
            return
        self.notify(f"trace written to {path}")
