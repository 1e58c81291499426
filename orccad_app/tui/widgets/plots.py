"""Live plots of a run's key values: one sparkline per series component."""

from __future__ import annotations

from collections import deque

from textual.app import ComposeResult
from textual.containers import VerticalScroll
from textual.widgets import Label, Sparkline

__all__ = ["Plots", "FIRST"]

FIRST = ("tracking error", ".q[", ".depth", ".heading", ".attitude[2]")
"""Series shown first when present (the task error, the arm's joints, the AUV's depth and
heading); every other series follows in name order."""


def _order(name: str) -> tuple[int, str]:
    for rank, key in enumerate(FIRST):
        if name == key or key in name:
            return rank, name
    return len(FIRST), name


class Plots(VerticalScroll):
    """Series added as they first appear (the task error, the robots' sensors), each with
    its latest value and range over the window shown."""

    DEFAULT_CSS = """
    Plots { height: 1fr; }
    Plots Label { width: 100%; color: $text-muted; }
    Plots Sparkline { height: 2; margin-bottom: 1; }
    """

    def __init__(self, window: int = 200, **kwargs) -> None:
        super().__init__(**kwargs)
        self.window = window
        self._data: dict[str, deque[float]] = {}

    def compose(self) -> ComposeResult:
        yield Label("no samples yet", id="plots-empty")

    def add_samples(self, samples: dict[str, list[float]]) -> None:
        """Append new samples (series name -> values)."""
        for name in sorted(samples, key=_order):
            data = self._data.get(name)
            if data is None:
                data = self._data[name] = deque(maxlen=self.window)
                self._mount_series(name)
            data.extend(samples[name])
            self._refresh(name)

    @property
    def series(self) -> list[str]:
        """The names of the series shown."""
        return list(self._data)

    def latest(self, name: str) -> float | None:
        data = self._data.get(name)
        return data[-1] if data else None

    def _key(self, name: str) -> str:
        return "".join(c if c.isalnum() else "-" for c in name)

    def _mount_series(self, name: str) -> None:
        for empty in self.query("#plots-empty"):
            empty.remove()
        key = self._key(name)
        later = [other for other in self._data if other != name and _order(other) > _order(name)]
        before = self.query_one(f"#label-{self._key(min(later, key=_order))}") if later else None
        self.mount(Label(name, id=f"label-{key}"), Sparkline([], id=f"plot-{key}"),
                   before=before)

    def _refresh(self, name: str) -> None:
        data, key = self._data[name], self._key(name)
        self.query_one(f"#label-{key}", Label).update(
            f"{name}  {data[-1]: .4g}   ({min(data):.3g} … {max(data):.3g})")
        self.query_one(f"#plot-{key}", Sparkline).data = list(data)
