"""What the user can raise during a run: the mission's declared inputs (buttons, keys 1–9),
and, from a list (key ``i``), the observers' events ``X.E`` and the robots' plant faults."""

from __future__ import annotations

from typing import Any

from textual import on
from textual.app import ComposeResult
from textual.containers import Horizontal
from textual.widgets import Button, Input, Label, Select

from orccad_app.tui.messages import InputRequested

__all__ = ["InputBar"]


def _number(text: str, kind: str | None) -> Any:
    try:
        return int(text) if kind == "int" else float(text)
    except ValueError:
        return 1 if kind == "int" else 1.0


class InputBar(Horizontal):
    """Declared inputs in declaration order (key ``n`` raises the n-th); valued ones take the
    value typed in the field. ``events`` (``X.E``) and ``faults`` (``ROBOT.FAULT`` ->
    description) are offered in a list, injected with the same value field."""

    DEFAULT_CSS = """
    InputBar { height: 3; align-vertical: middle; }
    InputBar Button { min-width: 8; margin-right: 1; }
    InputBar Input { width: 12; }
    InputBar Select { width: 34; }
    InputBar Label { padding: 0 1; }
    """

    def __init__(self, inputs: list, events: list[str] = (), faults: dict[str, str] = None,
                 **kwargs) -> None:
        super().__init__(**kwargs)
        self.inputs = list(inputs)[:9]
        self.events = list(events)
        self.faults = dict(faults or {})

    def compose(self) -> ComposeResult:
        yield Label("inputs:" if self.inputs else "no declared input")
        for number, signal in enumerate(self.inputs, 1):
            yield Button(f"{number} {signal.name}", id=f"input-{signal.name}", compact=True)
        yield Input("1", id="input-value", placeholder="value", compact=True)
        options = [(f"fault {name}", name) for name in self.faults]
        options += [(f"event {name}", name) for name in self.events]
        if options:
            yield Select(options, id="injection", prompt="fault or event", compact=True)
            yield Button("i inject", id="inject", compact=True)

    @property
    def value_text(self) -> str:
        return self.query_one("#input-value", Input).value.strip()

    def request(self, number: int) -> None:
        """Raise the ``number``-th declared input (1-based), if there is one."""
        if 1 <= number <= len(self.inputs):
            self._raise(self.inputs[number - 1])

    def inject(self, name: str | None = None) -> None:
        """Inject ``name`` (default: the one selected in the list): a fault or an event."""
        if name is None and self.query("#injection"):
            value = self.query_one("#injection", Select).value
            name = value if isinstance(value, str) else None
        if name in self.faults:
            self.post_message(InputRequested(name, _number(self.value_text, None), fault=True))
        elif name in self.events:
            self.post_message(InputRequested(name))
        else:
            self.notify("choose a fault or an event in the list first", severity="warning")

    def _raise(self, signal) -> None:
        value = _number(self.value_text, signal.type) if signal.type else None
        self.post_message(InputRequested(signal.name, value))

    @on(Button.Pressed)
    def _pressed(self, event: Button.Pressed) -> None:
        if event.button.id == "inject":
            self.inject()
            return
        name = (event.button.id or "").removeprefix("input-")
        for signal in self.inputs:
            if signal.name == name:
                self._raise(signal)
