"""The final report of a run (``orccad run``'s text) and the trace export.

The export never overwrites a file silently (a second ``e`` confirms), writes atomically (a
temporary file renamed when complete: no truncated trace is ever visible) and shows its
progress (an MCAP conversion of a long run takes seconds)."""

from __future__ import annotations

from textual import on, work
from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Horizontal, VerticalScroll
from textual.message import Message
from textual.screen import Screen
from textual.widgets import Button, Footer, Header, Input, ProgressBar, Static

from orccad_app.tui.session import LiveSession

__all__ = ["ReportScreen"]


class _Exported(Message):
    def __init__(self, path: str, error: str | None) -> None:
        super().__init__()
        self.path = path
        self.error = error


class _Progress(Message):
    def __init__(self, fraction: float) -> None:
        super().__init__()
        self.fraction = fraction


class ReportScreen(Screen):
    """Shows the report; ``e`` writes the trace to the path typed (``.csv`` or ``.mcap``)."""

    AUTO_FOCUS = "#report-body"

    BINDINGS = [
        Binding("e", "export", "Export trace",
                tooltip="write the trace to the path in the field (.csv or .mcap)"),
        Binding("escape", "app.pop_screen", "Back to the run"),
        Binding("q", "app.quit", "Quit"),
    ]

    def __init__(self, session: LiveSession, report: str) -> None:
        super().__init__()
        self.session = session
        self.report = report
        self._confirm: str | None = None  # a path that exists and may now be overwritten
        self.exporting = False

    def compose(self) -> ComposeResult:
        yield Header()
        with VerticalScroll(id="report-body"):
            yield Static(self.report, id="report-text")
        with Horizontal(id="export-bar"):
            yield Input(f"{self.session.mission}-trace.mcap", id="export-path")
            yield Button("Export trace", id="export-button", variant="primary")
            yield ProgressBar(total=1.0, id="export-progress", show_eta=False)
        yield Footer(compact=True)

    def on_mount(self) -> None:
        self.title = f"ORCCAD — report {self.session.mission}"
        self.sub_title = self.session.result.status if self.session.result else ""
        self.query_one(ProgressBar).display = False

    @on(Button.Pressed, "#export-button")
    @on(Input.Submitted, "#export-path")
    def action_export(self) -> None:
        if self.exporting:
            self.notify("an export is under way", severity="warning")
            return
        path = self.query_one("#export-path", Input).value.strip()
        if not path:
            self.notify("type the trace's path first (.csv or .mcap)", severity="error")
            return
        from pathlib import Path

        overwrite = self._confirm == path
        if Path(path).exists() and not overwrite:
            self._confirm = path
            self.notify(f"{path} exists: press e again to overwrite it", severity="warning")
            return
        self._confirm = None
        self.exporting = True
        bar = self.query_one(ProgressBar)
        bar.display = True
        bar.update(progress=0.0)
        self._export(path, overwrite)

    @work(thread=True, exclusive=True, group="export")
    def _export(self, path: str, overwrite: bool) -> None:
        try:
            self.session.export(path, overwrite=overwrite,
                                progress=lambda f: self.post_message(_Progress(f)))
        except FileExistsError:
            self.post_message(_Exported(path, f"{path} exists (created meanwhile): press e "
                                              "again to overwrite it"))
        except Exception as error:  # a bad path or extension: tell, do not crash
            self.post_message(_Exported(path, f"export failed: {error}"))
        else:
            self.post_message(_Exported(path, None))

    @on(_Progress)
    def _progress(self, message: _Progress) -> None:
        self.query_one(ProgressBar).update(progress=message.fraction)

    @on(_Exported)
    def _exported(self, message: _Exported) -> None:
        self.exporting = False
        self.query_one(ProgressBar).display = False
        if message.error:
            self.notify(message.error, severity="error")
        else:
            self.notify(f"trace written to {message.path}")
