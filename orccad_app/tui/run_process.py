"""A live run in its own process, so that drawing the screen never holds the run back.

The console draws with Textual in its process; a run in a thread of that process shares the
interpreter (the GIL) with the drawing, and a frame drawn is time the run waits. With
:func:`run_forked` the planned run is executed in a **child process forked after planning**
(the child has the very plan, models and observers the console built; nothing is re-planned
or re-loaded), while the console's process only receives its frames:

- child → console, one pipe: each :class:`~orccad_app.tui.live.LiveUpdate` the observer
  posts, then the run's end (:class:`RunEnded`: the report, what the user raised, the
  reaction at which an abort ended it) or the error that ended it;
- console → child, another pipe: the user's requests (:class:`Request`: pulses, holds,
  releases, faults, speed changes, abort, "frame taken"), applied in the child by a thread
  that calls the observer as the console's thread would in one process
  (:meth:`~orccad_app.tui.live.LiveObserver.apply`); their due instants are decided in the
  child at its next reaction, as in one process.

No process is left behind: the console waits for the child after its end; if the console
closes the request pipe (it ends, or its thread fails) the child's run is aborted at its next
reaction and the child exits. The child never writes to the terminal nor runs the console's
exit handlers (it ends with ``os._exit``), ignores the terminal's Ctrl-C (the console decides)
and leaves the console's signal wake-up descriptor alone.

The run is the same as in one process (same plan, seed, injections; the user's inputs take
effect at the instants the child reports), which ``tests/tui`` checks against ``orccad run``.
"""

from __future__ import annotations

import dataclasses
import os
import signal
import threading
from dataclasses import dataclass
from multiprocessing.connection import Connection, Pipe
from typing import Any, Callable

from orccad_app.diagnostics import OrccadError
from orccad_app.trace.report import InjectionRecord

__all__ = ["RunEnded", "Request", "run_forked", "can_fork"]


def can_fork() -> bool:
    """Whether runs can go to a child process here (``os.fork`` exists: not on Windows)."""
    return hasattr(os, "fork")


@dataclass(frozen=True)
class Request:
    """What the user asked of a run in another process: ``what`` is ``pulse``, ``hold``,
    ``release``, ``fault``, ``abort`` (``name``: the reason), ``pace`` (``value``: the
    factor, ``None`` as fast as possible) or ``taken`` (the screen took a frame)."""

    what: str
    name: str = ""
    value: Any = None


@dataclass(frozen=True)
class RunEnded:
    """How a run in the child ended: its report (``RunReport``; its ``result.modules`` left
    out: the console has the same plan), what the user raised, the abort's reaction."""

    report: Any
    injected: tuple[InjectionRecord, ...]
    aborted_at: int | None
    reactions: int


class _Requests:
    """The console's end of the request pipe: sends from any thread; once closed (or the
    child gone), a request is dropped (the run is over: it could not take effect)."""

    def __init__(self, connection: Connection) -> None:
        self._connection, self._lock, self._open = connection, threading.Lock(), True

    def send(self, request: Request) -> None:
        with self._lock:
            if not self._open:
                return
            try:
                self._connection.send(request)
            except OSError:  # the child has ended
                self._open = False

    def close(self) -> None:
        with self._lock:
            self._open = False
            self._connection.close()


def _child(execute: Callable[[], Any], observer: Any, updates: Connection,
           requests: Connection) -> int:
    """In the child: apply requests on a thread, run, send the end. The exit status."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C is the console's to decide
    try:
        signal.set_wakeup_fd(-1)  # the console's event loop's, not ours
    except ValueError:  # not the main thread of the child (it always is after a fork)
        pass
    observer.post = lambda update: updates.send(("update", update))

    def serve() -> None:
        while True:
            try:
                request = requests.recv()
            except (EOFError, OSError):  # the console is gone: end the run
                observer.apply(Request("abort", "the console closed"))
                return
            observer.apply(request)

    threading.Thread(target=serve, name="orccad-requests", daemon=True).start()
    try:
        report = execute()
        result = dataclasses.replace(report.result, modules={})  # not picklable; same plan
        updates.send(("report", RunEnded(dataclasses.replace(report, result=result),
                                       tuple(observer.injected), observer.aborted_at,
                                       observer.reactions)))
        return 0
    except OrccadError as error:
        _tell(updates, ("error", error.message))
    except BaseException as error:  # noqa: BLE001 — reported to the console, then exit
        _tell(updates, ("error", f"{type(error).__name__}: {error}"))
    return 1


def _tell(updates: Connection, message: tuple[str, Any]) -> None:
    try:
        updates.send(message)
    except OSError:  # the console is gone: nobody to tell
        pass


def run_forked(execute: Callable[[], Any], observer: Any,
               post: Callable[[Any], None]) -> RunEnded:
    """Run ``execute()`` (the planned run, returning its ``RunReport``) in a forked child;
    ``observer`` is the run's :class:`~orccad_app.tui.live.LiveObserver` (in the child it
    posts through the pipe; here it forwards the user's requests to the child); each frame
    goes to ``post`` on this (the calling) thread. Returns when the child's run has ended;
    raises :class:`OrccadError` with the child's error."""
    updates_in, updates_out = Pipe(duplex=False)
    requests_in, requests_pipe = Pipe(duplex=False)
    requests_out = _Requests(requests_pipe)
    observer.forward(requests_out.send)  # requests made from now on wait in the pipe
    with observer.forking():  # no lock of the run's is copied held by the UI's thread
        pid = os.fork()
    if pid == 0:  # the child (its only thread)
        status = 1
        try:
            observer.local()
            updates_in.close()
            requests_pipe.close()
            status = _child(execute, observer, updates_out, requests_in)
        finally:
            os._exit(status)
    updates_out.close()
    requests_in.close()
    try:
        while True:
            try:
                kind, payload = updates_in.recv()
            except EOFError:
                raise OrccadError("the run's process ended without its report") from None
            if kind == "update":
                post(payload)
            elif kind == "report":
                return payload
            else:
                raise OrccadError(payload)
    finally:
        observer.forward(None)
        requests_out.close()  # the child, if still running, aborts its run and exits
        updates_in.close()
        os.waitpid(pid, 0)
