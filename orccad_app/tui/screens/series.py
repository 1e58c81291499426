"""Choose the series the run screen plots (key ``p``)."""

from __future__ import annotations

from textual import on
from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Vertical
from textual.screen import ModalScreen
from textual.widgets import Button, Label, SelectionList

__all__ = ["SeriesScreen"]


class SeriesScreen(ModalScreen[list[str] | None]):
    """A list of ``series`` with the ``shown`` ones ticked; returns the ticked ones (``None``
    when cancelled). Set-points (``qd[i]``) are drawn with their measurement, not chosen."""

    DEFAULT_CSS = """
    SeriesScreen { align: center middle; }
    SeriesScreen > Vertical { width: 56; max-width: 95%; height: auto; max-height: 90%;
                              border: round $accent; background: $surface; padding: 0 1; }
    SeriesScreen SelectionList { height: auto; max-height: 16; }
    SeriesScreen Button { margin-top: 1; }
    """

    BINDINGS = [Binding("escape", "cancel", "Cancel"), Binding("enter", "ok", "Plot them")]

    def __init__(self, series: list[str], shown: list[str]) -> None:
        super().__init__()
        self.series = [name for name in series if not name.startswith("qd[")]
        self.shown = set(shown)

    def compose(self) -> ComposeResult:
        with Vertical():
            yield Label("series to plot (space ticks, enter plots):")
            yield SelectionList[str](*[(name, name, name in self.shown) for name in self.series],
                                     id="series-list")
            yield Button("Plot", id="series-ok", variant="primary")

    def action_ok(self) -> None:
        self.dismiss(list(self.query_one(SelectionList).selected))

    @on(Button.Pressed, "#series-ok")
    def _ok(self) -> None:
        self.action_ok()

    def action_cancel(self) -> None:
        self.dismiss(None)
