"""What the user can raise during a run: the mission's declared inputs (buttons), then the
observers' events ``X.E``, on keys 1–9; from a list (key ``i``, type to search), the events
and the robots' plant faults.

An input is raised as a **pulse** (present in one instant) or, in **hold** mode (key ``h``),
held: present in every instant until the same key releases it (a terminal reports no key
release, so a hold latches). A valued input takes the value typed in the field, parsed by its
declared type (``int``, ``float``, ``bool``, ``vector``, ``string``): a value that does not
parse is refused with what is expected, never replaced by a default.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from textual import on
from textual.app import ComposeResult
from textual.containers import Horizontal
from textual.widgets import Button, Input, Label, Select

from orccad_app.tui.messages import InputRequested
from orccad_app.tui.session import parse_value

__all__ = ["InputBar", "MODES"]

MODES = ("pulse", "hold")


class InputBar(Horizontal):
    """Declared inputs in declaration order, then ``events`` (``X.E``): key ``n`` raises the
    n-th (or holds/releases it in hold mode). ``events`` and ``faults`` (``ROBOT.FAULT`` ->
    description) are offered in a list, injected with key ``i``."""

    DEFAULT_CSS = """
    InputBar { height: 3; align-vertical: middle; }
    InputBar Button { min-width: 6; margin-right: 1; }
    InputBar Button.-held { background: $warning; color: $background; }
    InputBar #input-value { width: 16; }
    InputBar Select { width: 30; }
    InputBar Label { padding: 0 1; }
    """

    def __init__(self, inputs: list, events: Sequence[str] = (),
                 faults: dict[str, str] | None = None,
                 **kwargs) -> None:
        super().__init__(**kwargs)
        self.inputs = list(inputs)
        self.events = list(events)
        self.keyed = [*[s.name for s in self.inputs], *self.events][:9]
        """What keys 1–9 raise, in order."""
        self.faults = dict(faults or {})
        self.mode = "pulse"
        self.held: set[str] = set()

    def compose(self) -> ComposeResult:
        yield Button("h pulse", id="input-mode", compact=True,
                     tooltip="h: pulse (one instant) or hold (until pressed again)")
        for number, signal in enumerate(self.inputs[:9], 1):
            kind = f": {signal.type}" if signal.type else ""
            yield Button(f"{number} {signal.name}", id=f"input-{signal.name}", compact=True,
                         tooltip=f"input {signal.name}{kind}")
        keyed_events = len(self.keyed) - min(len(self.inputs), 9)
        if keyed_events:
            first = len(self.keyed) - keyed_events + 1
            yield Label(f"{first}–{len(self.keyed)} events" if keyed_events > 1
                        else f"{first} event")
        valued = [f"{s.name}: {s.type}" for s in self.inputs if s.type]
        if self.faults:
            valued.append("fault: float")
        if valued:
            yield Input("", id="input-value", placeholder=", ".join(valued), compact=True)
        options = [(f"{self._key(name)}event {name}", name) for name in self.events]
        options += [(f"fault {name}", name) for name in self.faults]
        if options:
            yield Select(options, id="injection", prompt="fault/event (type: search)",
                         compact=True)
            yield Button("i inject", id="inject", compact=True)
        if not self.inputs and not options:
            yield Label("this mission declares no input and its robots have no fault")

    def _key(self, name: str) -> str:
        return f"{self.keyed.index(name) + 1} " if name in self.keyed else ""

    @property
    def value_text(self) -> str:
        found = self.query("#input-value")
        return found.first(Input).value.strip() if found else ""

    def set_mode(self, mode: str) -> None:
        self.mode = mode
        self.query_one("#input-mode", Button).label = f"h {mode}"

    def cycle_mode(self) -> None:
        self.set_mode(MODES[(MODES.index(self.mode) + 1) % len(MODES)])

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
            try:
                value = parse_value(self.value_text, "float", name)
            except ValueError as error:
                self.notify(f"fault {name}: {error} (type it in the value field)",
                            severity="error")
                return
            self.post_message(InputRequested(name, value, fault=True))
        elif name in self.events:
            self.post_message(InputRequested(name))
        else:
            self.notify("choose a fault or an event in the list first", severity="warning")

    def _value(self, signal) -> tuple[bool, Any]:
        if not signal.type:
            return True, None
        try:
            return True, parse_value(self.value_text, signal.type, signal.name)
        except ValueError as error:
            self.notify(str(error), severity="error")
            return False, None

    def _raise(self, signal) -> None:
        if signal.name in self.held:  # pressed again: release, whatever the mode
            self.post_message(InputRequested(signal.name, hold=False, release=True))
            self._show_held(signal.name, False)
            return
        ok, value = self._value(signal)
        if not ok:
            return
        hold = self.mode == "hold"
        self.post_message(InputRequested(signal.name, value, hold=hold))
        if hold:
            self._show_held(signal.name, True)

    def _show_held(self, name: str, held: bool) -> None:
        (self.held.add if held else self.held.discard)(name)
        button = self.query_one(f"#input-{name}", Button)
        button.set_class(held, "-held")
        number = self.keyed.index(name) + 1
        button.label = f"{number} {name}{' ■' if held else ''}"

    @on(Button.Pressed)
    def _pressed(self, event: Button.Pressed) -> None:
        if event.button.id == "inject":
            self.inject()
            return
        if event.button.id == "input-mode":
            self.cycle_mode()
            return
        name = (event.button.id or "").removeprefix("input-")
        for signal in self.inputs:
            if signal.name == name:
                self._raise(signal)
