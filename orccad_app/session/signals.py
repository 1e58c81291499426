"""Ctrl-C and SIGTERM during a run, scoped to it.

While a run goes, the first Ctrl-C or SIGTERM ends it after the current event (status
``aborted``, the report printed, the trace complete: nothing is cut mid-sample); a second one
interrupts at once. The previous handlers are restored when the run ends, whatever the way, so
nothing leaks into the rest of the process (an in-process test harness, the next run).
"""

from __future__ import annotations

import signal
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from types import FrameType

from orccad_app.mission.run import INTERRUPTED, TERMINATED, MissionRun, Terminated

__all__ = ["signals_end_the_run"]

_REASONS = {signal.SIGINT: INTERRUPTED, signal.SIGTERM: TERMINATED}


@contextmanager
def signals_end_the_run(mission_run: MissionRun, *, enabled: bool = True) -> Iterator[None]:
    """Within the block, Ctrl-C and SIGTERM end ``mission_run`` (see the module docstring).
    Does nothing when not ``enabled`` or outside the main thread (signal handlers belong to
    it: the TUI runs in a worker thread)."""
    if not enabled or threading.current_thread() is not threading.main_thread():
        yield
        return

    def on_signal(signum: int, frame: FrameType | None) -> None:
        if mission_run.stopping:
            raise Terminated if signum == signal.SIGTERM else KeyboardInterrupt
        mission_run.abort(_REASONS[signal.Signals(signum)])

    previous = {sent: signal.signal(sent, on_signal) for sent in _REASONS}
    try:
        yield
    finally:
        for sent, handler in previous.items():
            signal.signal(sent, handler)
