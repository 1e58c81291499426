"""The controller process: started, spoken to over a Unix socket, watched, always ended.

:class:`ControllerProcess` starts the compiled controller (:mod:`orccad_app.sil.build`) with
one end of a Unix ``socketpair`` as its file descriptor, checks that it runs the expected
table (:attr:`~orccad_app.sil.generate.table.ModuleTable.digest`), and exchanges one request and one
reply at a time (the frames of ``orccad_app/sil/c/orccad_lockstep.c``).

Every reply is the controller's **heartbeat**: a controller that does not answer within
``heartbeat_s`` wall seconds is *hung*; one whose socket closes is *crashed* (with its exit
status or the signal that killed it). Either way the process is killed and reaped at once and
:class:`ControllerFailure` names the reason — the mission then ends ``failed`` with it, the
trace complete. :meth:`ControllerProcess.close` ends a healthy controller (``QUIT``, then
``SIGKILL`` after a grace period), so that no process is ever left behind; the controller
also ends by itself when the plant server's end of the socket closes (the plant server
killed).
"""

from __future__ import annotations

import signal
import socket
import struct
import subprocess
from collections.abc import Sequence
from enum import IntEnum
from pathlib import Path

from orccad_app.executive.task_runtime import ComputeError

__all__ = ["ControllerFailure", "ControllerProcess", "DEFAULT_HEARTBEAT_S", "Op", "Reply"]

DEFAULT_HEARTBEAT_S = 10.0
"""How long the plant server waits for a reply before the controller is declared hung [s]."""
_REQUEST = struct.Struct("=IIdII")
_REPLY = struct.Struct("=II")
_INT = struct.Struct("=q")
_QUIT_GRACE_S = 1.0


class Op(IntEnum):
    """Request operations (``orccad_lockstep.c``)."""

    HELLO = 1
    START = 2
    PARAM = 3
    INIT = 4
    COMPUTE = 5
    PING = 6
    QUIT = 7
    ACTIVATE = 8
    KILL = 9
    RESET = 10
    EPOCH = 11
    REACT = 12
    INPUT = 13
    PARAMS = 14


class Reply(IntEnum):
    """A reply's status (``enum orc_status`` of ``orccad_wire.h``)."""

    OK = 0
    NO_SUCH_MODULE = 1
    """The request's Module-Task (or one in its data) is not in the controller's table."""
    BAD_PARAMS = 2
    """Parameter words outside the Module-Task's."""
    NO_SUCH_KIND = 3
    """The Module-Task's kind has no C in this controller."""
    UNKNOWN_OP = 4
    """An operation this controller does not serve."""
    BAD_REACTION = 5
    """The automaton refused the reaction's words."""
    INPUTS_FULL = 6
    """More inputs ahead than a reaction period can hold."""
    BAD_WORDS = 7
    """The request's data has not the words its operation takes."""

    @property
    def reason(self) -> str:
        """The status in words (its docstring's first line)."""
        return {Reply.OK: "ok",
                Reply.NO_SUCH_MODULE: "no such Module-Task in its table",
                Reply.BAD_PARAMS: "parameter words outside the Module-Task's",
                Reply.NO_SUCH_KIND: "the Module-Task's kind has no C in this controller",
                Reply.UNKNOWN_OP: "an operation it does not serve",
                Reply.BAD_REACTION: "the automaton refused the reaction's words",
                Reply.INPUTS_FULL: "more inputs ahead than a reaction period can hold",
                Reply.BAD_WORDS: "the data has not the words the operation takes"}[self]


class ControllerFailure(ComputeError):
    """The controller process crashed, hung or answered wrongly: the run ends ``failed``."""


class ControllerProcess:
    """A running controller (see the module docstring).

    :param executable: the compiled controller.
    :param modules: the number of Module-Tasks of its table.
    :param digest: the table's digest, which the controller must answer.
    :param heartbeat_s: the longest wait for one reply [wall s].
    :param arguments: its arguments after ``--fd N``.
    :param wrapper: a command that runs it (``qemu-aarch64`` for a cross-built controller).
    """

    def __init__(self, executable: Path, modules: int, digest: str,
                 heartbeat_s: float = DEFAULT_HEARTBEAT_S,
                 arguments: tuple[str, ...] = (), wrapper: tuple[str, ...] = ()) -> None:
        self.heartbeat_s = heartbeat_s
        self.failure: str | None = None
        self.supervisor_writes = 0
        """Parameter words the supervisor wrote into the controller (``PARAM``: run-time
        arguments and type-1 updates the controller does not apply itself)."""
        ours, theirs = socket.socketpair(socket.AF_UNIX, socket.SOCK_STREAM)
        try:
            self.process = subprocess.Popen(
                [*wrapper, str(executable), "--fd", str(theirs.fileno()), *arguments],
                pass_fds=[theirs.fileno()],
                stdin=subprocess.DEVNULL, start_new_session=True)
        except OSError as error:
            ours.close()
            raise ControllerFailure(f"the controller process could not start: "
                                    f"{error.strerror or error}") from None
        finally:
            theirs.close()
        ours.settimeout(heartbeat_s)
        self._socket = ours
        self.pid = self.process.pid
        try:
            answer = self.request_words(Op.HELLO, b"")
        except BaseException:  # Ctrl-C or SIGTERM while waiting: nobody else can end it
            self.kill()
            raise
        got_modules = _INT.unpack_from(answer)[0] if len(answer) >= 8 else -1
        got_digest = answer[8:72].split(b"\0")[0].decode(errors="replace")
        if got_modules != modules or got_digest != digest:
            self._fail(f"the controller runs another table ({got_modules} Module-Tasks, "
                       f"digest {got_digest}; expected {modules}, {digest})")

    @property
    def alive(self) -> bool:
        """True while the process runs."""
        return self.process.poll() is None

    def request(self, op: Op, module: int = 0, t_s: float = 0.0, values: Sequence[float] = (),
                offset: int = 0) -> tuple[float, ...]:
        """Send one request and wait for its reply (the heartbeat); the reply's doubles."""
        payload = struct.pack(f"={len(values)}d", *values) if values else b""
        body = self._exchange(op, module, t_s, offset, payload)
        return struct.unpack(f"={len(body) // 8}d", body) if body else ()

    def request_words(self, op: Op, payload: bytes, module: int = 0, t_s: float = 0.0) -> bytes:
        """Send one request whose data are ``payload`` (8-byte words, already packed: doubles,
        or integers where the operation takes them) and wait for its reply; the reply's
        words, unpacked by the caller."""
        return self._exchange(op, module, t_s, 0, payload)

    def request_ints(self, op: Op, values: Sequence[int] = (), module: int = 0,
                     t_s: float = 0.0) -> tuple[int, ...]:
        """Send one request whose data are integer words (Module-Task indices) and wait for
        its reply; the reply's integer words."""
        reply = self.request_words(op, struct.pack(f"={len(values)}q", *values), module, t_s)
        return struct.unpack(f"={len(reply) // 8}q", reply)

    def _exchange(self, op: Op, module: int, t_s: float, offset: int, payload: bytes) -> bytes:
        if self.failure is not None:
            raise ControllerFailure(self.failure)
        frame = _REQUEST.pack(op, module, t_s, len(payload) // 8, offset) + payload
        try:
            self._socket.sendall(frame)
            head = self._receive(_REPLY.size, op)
            status, count = _REPLY.unpack(head)
            body = self._receive(8 * count, op) if count else b""
        except OSError as error:  # a closed or reset socket: the process is gone
            self._fail(self._crash_reason(f"the socket failed ({error.strerror or error})"))
        if status != Reply.OK:
            try:
                why = Reply(status).reason
            except ValueError:
                why = f"an unknown status {status}"
            self._fail(f"the controller refused request {op.name} for Module-Task {module}: "
                       f"{why}")
        return body

    def _receive(self, size: int, op: Op) -> bytes:
        chunks, left = [], size
        while left:
            try:
                chunk = self._socket.recv(left)
            except TimeoutError:
                self._fail(f"the controller process hung: no answer to {op.name} within "
                           f"{self.heartbeat_s:g} s (its heartbeat)")
            if not chunk:
                self._fail(self._crash_reason("it closed the socket"))
            chunks.append(chunk)
            left -= len(chunk)
        return b"".join(chunks)

    def _crash_reason(self, what: str) -> str:
        try:
            code = self.process.wait(timeout=_QUIT_GRACE_S)
        except subprocess.TimeoutExpired:
            return f"the controller process stopped answering: {what}"
        if code < 0:
            try:
                name = signal.Signals(-code).name
            except ValueError:
                name = f"signal {-code}"
            return f"the controller process crashed: killed by {name}"
        return f"the controller process crashed: it exited with status {code} ({what})"

    def _fail(self, reason: str) -> None:
        self.failure = reason
        self.kill()
        raise ControllerFailure(reason)

    def kill(self) -> None:
        """Kill the process now and reap it (idempotent)."""
        if self.process.poll() is None:
            self.process.kill()
        try:
            self.process.wait(timeout=5.0)
        except subprocess.TimeoutExpired:  # pragma: no cover (SIGKILL cannot be ignored)
            pass
        self._socket.close()

    def close(self) -> None:
        """End the controller: ``QUIT`` when healthy, then ``SIGKILL`` if it is still there
        after a grace period; always reaped."""
        if self.failure is None and self.process.poll() is None:
            try:
                self._socket.settimeout(_QUIT_GRACE_S)
                self._socket.sendall(_REQUEST.pack(Op.QUIT, 0, 0.0, 0, 0))
                self.process.wait(timeout=_QUIT_GRACE_S)
            except (OSError, subprocess.TimeoutExpired):
                pass
        self.kill()

    def __enter__(self) -> ControllerProcess:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
