"""Live time-series plots of a run: a time axis, the whole mission or a rolling window, chosen
series, each measurement drawn over its set-point, and markers at task starts, exceptions and
injections.

Drawn with textual-plotext (plotext in a Textual widget): a real plot with axes, ticks and a
legend in the terminal, which Textual's ``Sparkline`` (no axis, no time, one series) cannot be.
"""

from __future__ import annotations

import re
import time
from dataclasses import dataclass

from textual.app import ComposeResult
from textual.containers import Vertical
from textual.widgets import Label
from textual_plotext import PlotextPlot

__all__ = ["Plots", "Marker", "FIRST", "default_series", "setpoint_of", "REDRAW_S",
           "BUSY_PLOT_FRAMES"]

FIRST = ("tracking error", ".q[", ".depth", ".heading", ".attitude[2]")
"""Series shown first when present (the task error, the arm's joints, the AUV's depth and
heading); every other series follows in name order."""

ROLLING_S = 10.0
"""Width of the rolling window [s]."""

_MAX_POINTS = 240  # per series drawn: two braille dots per column of a wide terminal

REDRAW_S = 0.25
"""Plots are redrawn at most this often [s] (wall time) while samples arrive."""
BUSY_PLOT_FRAMES = 4
"""... and once every this many frames while the run goes as fast as it can (about once per
second of the run's CPU time, :data:`~orccad_app.tui.live.BUSY_FRAME_S`): a plot costs more
to draw than a second of the arm's simulation, and the run shares the interpreter with the
screen."""


@dataclass(frozen=True)
class Marker:
    """A vertical line on the plots: ``kind`` is ``task``, ``exception`` or ``input``."""

    t_s: float
    kind: str
    label: str


_MARKER_COLOR = {"task": "green", "exception": "red", "input": "orange", "fault": "orange"}


def _order(name: str) -> tuple[int, str]:
    for rank, key in enumerate(FIRST):
        if name == key or key in name:
            return rank, name
    return len(FIRST), name


def setpoint_of(name: str, names) -> str | None:
    """The set-point series of measurement ``name``: ``qd[i]`` for ``ROBOT.q[i]``."""
    match = re.fullmatch(r"\w+\.q\[(\d+)\]", name)
    if match and f"qd[{match.group(1)}]" in names:
        return f"qd[{match.group(1)}]"
    return None


def default_series(names) -> list[str]:
    """What is shown before the user chooses: the robot's joints (with their set-points drawn
    over them), else the first series in :data:`FIRST` order."""
    measured = [n for n in sorted(names) if setpoint_of(n, names) or re.fullmatch(
        r"\w+\.q\[\d+\]", n)]
    if measured:
        return measured
    ranked = sorted((n for n in names if not n.startswith("qd[")), key=_order)
    return ranked[:1]


class Plots(Vertical):
    """Series added as they first appear; :attr:`chosen` are drawn (``None``: the default),
    over the whole mission or the last :data:`ROLLING_S` seconds (:attr:`rolling`)."""

    DEFAULT_CSS = """
    Plots { height: 1fr; }
    Plots #plots-caption { width: 100%; color: $text-muted; height: 1; }
    Plots PlotextPlot { height: 1fr; }
    """

    def __init__(self, **kwargs) -> None:
        super().__init__(**kwargs)
        self._data: dict[str, tuple[list[float], list[float]]] = {}
        self.markers: list[Marker] = []
        self.chosen: list[str] | None = None
        self.rolling = False
        self._dirty = False
        self.min_interval_s = REDRAW_S
        """The least wall time between two redraws [s]."""
        self._drawn_at = 0.0

    def compose(self) -> ComposeResult:
        yield Label("no samples yet", id="plots-caption")
        yield PlotextPlot(id="plot")

    def on_mount(self) -> None:
        self.set_interval(REDRAW_S, self._redraw_if_dirty)
        self.redraw()

    def add_samples(self, samples: dict[str, list[tuple[float, float]]]) -> None:
        """Append new ``(t [s], value)`` samples per series."""
        for name, points in samples.items():
            times, values = self._data.setdefault(name, ([], []))
            for t, value in points:
                times.append(t)
                values.append(value)
        self._dirty = self._dirty or bool(samples)

    def add_markers(self, markers: list[Marker]) -> None:
        self.markers.extend(markers)
        self._dirty = self._dirty or bool(markers)

    @property
    def series(self) -> list[str]:
        """The names of the series recorded, in display order."""
        return sorted(self._data, key=_order)

    @property
    def shown(self) -> list[str]:
        """The series drawn now (the chosen ones that have samples)."""
        chosen = self.chosen if self.chosen is not None else default_series(self._data)
        return [name for name in chosen if name in self._data]

    def latest(self, name: str) -> float | None:
        data = self._data.get(name)
        return data[1][-1] if data and data[1] else None

    def choose(self, names: list[str]) -> None:
        self.chosen = list(names)
        self.redraw()

    def toggle_window(self) -> None:
        self.rolling = not self.rolling
        self.redraw()

    def _redraw_if_dirty(self) -> None:
        if self._dirty and time.monotonic() - self._drawn_at >= self.min_interval_s - 0.01:
            self.redraw()

    def _window(self) -> tuple[float, float] | None:
        ends = [times[-1] for times, _ in self._data.values() if times]
        if not ends:
            return None
        end = max(ends)
        return (max(0.0, end - ROLLING_S) if self.rolling else 0.0), max(end, 1e-3)

    def redraw(self) -> None:
        """Draw the shown series (and their set-points) with the markers in the window."""
        self._dirty = False
        self._drawn_at = time.monotonic()
        plot = self.query_one(PlotextPlot)
        plt = plot.plt
        plt.clear_data()
        plt.clear_figure()
        window = self._window()
        caption = self.query_one("#plots-caption", Label)
        if window is None:
            caption.update("no samples yet: the plots start with the first measurement",
                           layout=False)  # one line, always
            plot.refresh()
            return
        start, end = window
        shown = self.shown
        drawn = []
        for name in shown:
            drawn.append(name)
            self._plot(plt, name, start, "braille")
            setpoint = setpoint_of(name, self._data)
            if setpoint is not None:
                self._plot(plt, setpoint, start, "dot")
        for marker in self.markers:
            if start <= marker.t_s <= end:
                plt.vline(marker.t_s, _MARKER_COLOR.get(marker.kind, "gray"))
        plt.xlim(start, end)
        plt.xlabel("t [s]")
        over = " (set-points dotted)" if any(setpoint_of(n, self._data) for n in shown) else ""
        span = f"last {ROLLING_S:g} s" if self.rolling else "whole mission"
        caption.update(f"{', '.join(drawn) or 'nothing chosen'}{over} — {span}; markers: "
                       f"green task start, red exception, orange input/fault  "
                       f"[p] choose  [w] window", layout=False)
        plot.refresh()

    def _plot(self, plt, name: str, start: float, marker: str) -> None:
        times, values = self._data[name]
        first = next((i for i, t in enumerate(times) if t >= start), len(times))
        xs, ys = times[first:], values[first:]
        step = max(1, len(xs) // _MAX_POINTS)
        plt.plot(xs[::step], ys[::step], label=name, marker=marker)
