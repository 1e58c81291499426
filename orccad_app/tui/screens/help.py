"""The help screen (``?`` or F1): the keys of the screen it was opened on."""

from __future__ import annotations

from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import VerticalScroll
from textual.screen import ModalScreen, Screen
from textual.widgets import Static

__all__ = ["HelpScreen", "keys_of"]

_NAMES = {"space": "space", "escape": "esc", "question_mark": "?", "ctrl+p": "ctrl+p"}


def keys_of(screen: Screen) -> list[tuple[str, str]]:
    """``(key, what it does)`` for every binding of ``screen`` and of the app, in order."""
    rows: list[tuple[str, str]] = []
    seen: set[str] = set()
    for owner in (screen, screen.app):
        for binding in owner.BINDINGS:
            if not isinstance(binding, Binding):
                continue
            key = ", ".join(_NAMES.get(k, k) for k in binding.key.split(","))
            if key in seen or not (binding.description or binding.tooltip):
                continue
            seen.add(key)
            rows.append((key, binding.tooltip or binding.description))
    return rows


class HelpScreen(ModalScreen):
    """Lists the keys of ``screen`` (its title on top); any of ``escape``, ``?``, F1 closes."""

    DEFAULT_CSS = """
    HelpScreen { align: center middle; }
    HelpScreen > VerticalScroll { width: 72; max-width: 95%; height: auto; max-height: 90%;
                                  border: round $accent; background: $surface; padding: 0 1; }
    """

    BINDINGS = [Binding("escape,question_mark,f1,q", "dismiss", "Close")]

    def __init__(self, screen: Screen, intro: str = "") -> None:
        super().__init__()
        self.rows = keys_of(screen)
        self.heading = f"{screen.title or screen.app.title}: keys"
        self.intro = intro

    def compose(self) -> ComposeResult:
        width = max((len(key) for key, _ in self.rows), default=4) + 2
        lines = [f"[b]{self.heading}[/b]", ""]
        if self.intro:
            lines += [self.intro, ""]
        lines += [f"[b]{key:<{width}}[/b]{what}" for key, what in self.rows]
        lines += ["", "ctrl+p: command palette (open, run, check, inject, export, speed)",
                  "esc, ? or F1 closes this help"]
        with VerticalScroll():
            yield Static("\n".join(lines), id="help-text", markup=True)
