"""Buttons (and keys 1–9) raising the mission's declared input signals during a run."""

from __future__ import annotations

from textual import on
from textual.app import ComposeResult
from textual.containers import Horizontal
from textual.widgets import Button, Input, Label

from orccad_app.tui.messages import InputRequested

__all__ = ["InputBar"]


class InputBar(Horizontal):
    """One button per declared input, in declaration order (key ``n`` raises the n-th);
    valued inputs take the value typed in the field."""

    DEFAULT_CSS = """
    InputBar { height: 3; align-vertical: middle; }
    InputBar Button { min-width: 10; margin-right: 2; }
    InputBar Input { width: 14; }
    InputBar Label { padding: 0 1; }
    """

    def __init__(self, inputs: list, **kwargs) -> None:
        super().__init__(**kwargs)
        self.inputs = list(inputs)[:9]

    def compose(self) -> ComposeResult:
        if not self.inputs:
            yield Label("this mission declares no input")
            return
        yield Label("inputs:")
        for number, signal in enumerate(self.inputs, 1):
            yield Button(f"{number} {signal.name}", id=f"input-{signal.name}", compact=True)
        if any(signal.type for signal in self.inputs):
            yield Input("1.0", id="input-value", placeholder="value")

    def request(self, number: int) -> None:
        """Raise the ``number``-th input (1-based), if there is one."""
        if 1 <= number <= len(self.inputs):
            self._raise(self.inputs[number - 1])

    def _raise(self, signal) -> None:
        value = None
        if signal.type:
            text = self.query_one("#input-value", Input).value.strip()
            try:
                value = float(text) if signal.type == "float" else int(text)
            except ValueError:
                value = 1.0 if signal.type == "float" else 1
        self.post_message(InputRequested(signal.name, value))

    @on(Button.Pressed)
    def _pressed(self, event: Button.Pressed) -> None:
        name = (event.button.id or "").removeprefix("input-")
        for signal in self.inputs:
            if signal.name == name:
                self._raise(signal)
