"""SIGTERM during a command's work, ended as Ctrl-C ends it.

By default SIGTERM ends Python at once: no ``finally`` runs, so a child process (the C
compiler of ``orccad sil``, the controller) and the temporary files of the work would be left
behind. Within :func:`terminate_as_interrupt`, SIGTERM raises
:class:`~orccad_app.mission.run.Terminated` (a ``KeyboardInterrupt``) instead: every cleanup
runs and the command ends as interrupted (exit status 130). A run's own handling of the two
signals (:mod:`orccad_app.session.signals`: end the run after the current event) takes over
while the run goes and gives this one back after it.
"""

from __future__ import annotations

import signal
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from types import FrameType

__all__ = ["terminate_as_interrupt"]


@contextmanager
def terminate_as_interrupt() -> Iterator[None]:
    """Within the block, SIGTERM raises ``Terminated`` (see the module docstring); nothing
    outside the main thread, where signal handlers cannot be set."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    from orccad_app.mission.run import Terminated

    def on_term(signum: int, frame: FrameType | None) -> None:
        raise Terminated

    previous = signal.signal(signal.SIGTERM, on_term)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)
