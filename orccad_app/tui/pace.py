"""The speed of a live run (:class:`Pace`): paused, × factor, or as fast as possible;
set from the UI's thread, waited on by the executive's (:mod:`orccad_app.tui.live`)."""

from __future__ import annotations

import threading
import time
from contextlib import contextmanager
from typing import Callable, Iterator

__all__ = ["Pace", "new_event"]


def new_event(is_set: bool) -> threading.Event:
    """A new event, set or not."""
    event = threading.Event()
    if is_set:
        event.set()
    return event


class Pace:
    """Speed of a live run: ``factor`` simulated seconds per wall second, ``0`` paused,
    ``None`` as fast as possible. Thread-safe: set from the UI, waited on by the executive."""

    def __init__(self, factor: float | None = 1.0) -> None:
        self._lock = threading.Lock()
        self._resumed = threading.Event()
        self.factor: float | None = None
        self._anchor: tuple[float, int] | None = None
        self.stopped = False
        self._paused_since: float | None = None
        self._paused_s = 0.0
        self.on_change: Callable[[float | None], None] | None = None
        """Called with each new factor (a run in another process follows this one)."""
        self.set(factor)

    def set(self, factor: float | None) -> None:
        """Change the speed; pacing restarts from the current instant."""
        if factor is not None and factor < 0:
            raise ValueError(f"speed factor must be >= 0, got {factor!r}")
        with self._lock:
            now = time.perf_counter()
            if factor == 0 and self._paused_since is None:
                self._paused_since = now
            elif factor != 0 and self._paused_since is not None:
                self._paused_s += now - self._paused_since
                self._paused_since = None
            self.factor = factor
            self._anchor = None
            if factor == 0:
                self._resumed.clear()
            else:
                self._resumed.set()
        if self.on_change is not None:
            self.on_change(factor)

    def stop(self) -> None:
        """Release a paused run for good (the run is being aborted)."""
        with self._lock:
            self.stopped = True
            self._resumed.set()

    @contextmanager
    def forking(self) -> Iterator[None]:
        """Hold the pace while the calling thread forks: no other thread is then changing
        it (its lock and event are never copied held), and the child has a whole state."""
        with self._lock:
            yield

    def after_fork(self) -> None:
        """In the child of a fork made under :meth:`forking`: the event anew, as it was."""
        self._resumed = new_event(self._resumed.is_set())

    @property
    def paused(self) -> bool:
        return self.factor == 0

    @property
    def paused_s(self) -> float:
        """Wall time spent paused so far [s] (the current pause included)."""
        with self._lock:
            ongoing = 0.0 if self._paused_since is None else time.perf_counter() - self._paused_since
            return self._paused_s + ongoing

    @property
    def label(self) -> str:
        if self.factor is None:
            return "max"
        return "paused" if self.factor == 0 else f"{self.factor:g}×"

    def wait(self, t_ns: int) -> None:
        """Block until simulated instant ``t_ns`` is due on the wall clock."""
        self._resumed.wait()
        with self._lock:
            factor = self.factor
            if factor is None or factor == 0 or self.stopped:
                return
            if self._anchor is None:
                self._anchor = (time.perf_counter(), t_ns)
            wall, sim = self._anchor
        delay = wall + (t_ns - sim) / 1e9 / factor - time.perf_counter()
        if delay > 0:
            time.sleep(delay)
