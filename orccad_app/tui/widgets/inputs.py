"""What the user can raise during a run: the mission's declared inputs (buttons), then the
observers' events ``X.E``, on keys 1–9; from a list (key ``i``), the events and the robots'
plant faults."""

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
    """Declared inputs in declaration order, then ``events`` (``X.E``): key ``n`` raises the
    n-th; valued inputs take the value typed in the field. ``events`` and ``faults``
    (``ROBOT.FAULT`` -> description) are offered in a list too, injected with key ``i``."""

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
        self.inputs = list(inputs)
        self.events = list(events)
        self.keyed = [*[s.name for s in self.inputs], *self.events][:9]
        """What keys 1–9 raise, in order."""
        self.faults = dict(faults or {})

    def compose(self) -> ComposeResult:
        yield Label("inputs:" if self.inputs else "no declared input")
        for number, signal in enumerate(self.inputs[:9], 1):
            yield Button(f"{number} {signal.name}", id=f"input-{signal.name}", compact=True)
        keyed_events = len(self.keyed) - min(len(self.inputs), 9)
        if keyed_events:
            first = len(self.keyed) - keyed_events + 1
            yield Label(f"{first}–{len(self.keyed)}: events ▸" if keyed_events > 1
                        else f"{first}: event ▸")
        yield Input("1", id="input-value", placeholder="value", compact=True)
        options = [(f"{self._key(name)}event {name}", name) for name in self.events]
        options += [(f"fault {name}", name) for name in self.faults]
        if options:
            yield Select(options, id="injection", prompt="fault or event", compact=True)
            yield Button("i inject", id="inject", compact=True)

    def _key(self, name: str) -> str:
        return f"{self.keyed.index(name) + 1} " if name in self.keyed else ""

    @property
    def value_text(self) -> str:
        return self.query_one("#input-value", Input).value.strip()

    def request(self, number: int) -> None:
        """Raise what key ``number`` (1-based) stands for, if anything."""
        if not 1 <= number <= len(self.keyed):
            return
        name = self.keyed[number - 1]
        signal = next((s for s in self.inputs if s.name == name), None)
        if signal is not None:
            self._raise(signal)
        else:
            self.inject(name)

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
