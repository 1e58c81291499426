"""A progress line for long runs: simulated time against the horizon, on a terminal.

:class:`ProgressLine` observes a :class:`~orccad_app.mission.run.MissionRun` through the
mission hook ``on_reaction`` and rewrites one line of its stream at most every
``interval_s`` of wall time, after ``delay_s`` (short runs print nothing). It only reads the
reaction's time: a run with and without it is the same run.

:class:`StatusLine` is that line alone (``orccad check`` shows its states explored and
properties done with it).
"""

from __future__ import annotations

import time
from typing import TextIO

from orccad_app.mission.observer import MissionObserver

__all__ = ["ProgressLine", "StatusLine"]


class StatusLine:
    """One line of ``stream`` rewritten in place, at most every ``interval_s`` of wall time
    and not before ``delay_s`` (short tasks print nothing); erased by :meth:`close`.

    :param stream: where to write (a terminal: the line is rewritten with ``\\r``).
    :param delay_s: wall time [s] before the first line.
    :param interval_s: wall time [s] between two updates.
    """

    def __init__(self, stream: TextIO, *, delay_s: float = 1.0, interval_s: float = 0.5) -> None:
        self._stream = stream
        self.start = time.monotonic()
        self._next = self.start + delay_s
        self._interval_s = interval_s
        self._shown = False

    def due(self) -> bool:
        """Whether a new text would be shown now (cheap: call it before formatting one)."""
        return time.monotonic() >= self._next

    def show(self, text: str) -> None:
        """Show ``text`` if due."""
        now = time.monotonic()
        if now < self._next:
            return
        self._next = now + self._interval_s
        self._stream.write(f"\r\033[K  {text} ")
        self._stream.flush()
        self._shown = True

    def close(self) -> None:
        """Erase the line (if one was shown) so that what follows starts on a clean line."""
        if self._shown:
            self._stream.write("\r\033[K")
            self._stream.flush()
            self._shown = False


class ProgressLine(MissionObserver):
    """``simulated 12.3 s of 60 s (20 %), 4.1x real time`` on ``stream``, kept up to date.

    :param stream: where to write (a terminal: the line is rewritten with ``\\r``).
    :param until_ns: the run's horizon [ns].
    :param delay_s: wall time [s] before the first line.
    :param interval_s: wall time [s] between two updates.
    """

    def __init__(self, stream: TextIO, until_ns: int, *, delay_s: float = 1.0,
                 interval_s: float = 0.5) -> None:
        self._line = StatusLine(stream, delay_s=delay_s, interval_s=interval_s)
        self._until_ns = until_ns

    def on_reaction(self, t_ns: int, inputs: tuple[str, ...], outputs: tuple[str, ...],
                    status: str) -> None:
        line = self._line
        if not line.due():
            return
        simulated_s = t_ns / 1e9
        ratio = simulated_s / max(time.monotonic() - line.start, 1e-9)
        percent = 100.0 * t_ns / self._until_ns if self._until_ns else 0.0
        line.show(f"simulated {simulated_s:.1f} s of {self._until_ns / 1e9:g} s "
                  f"({percent:.0f} %), {ratio:.1f}x real time")

    def close(self) -> None:
        """Erase the line (if one was shown) so that the report starts on a clean line."""
        self._line.close()
