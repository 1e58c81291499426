"""A live run streamed to Foxglove over its WebSocket protocol (``orccad run --foxglove``).

:class:`FoxgloveLiveWriter` is a trace writer (the rows of
:class:`~orccad_app.trace.recorder.TraceRecorder`) that publishes the **same topics, schemas and
messages** as the MCAP trace (:class:`~orccad_app.trace.mcap_writer.TopicWriter`: one topic per
port or plant signal with a stable numeric schema, ``foxglove.Log`` on ``/log``…) on a
WebSocket server of the ``foxglove-sdk`` package, on loopback. Each message's log time is the
simulated instant [ns]; the server advertises the ``time`` capability and broadcasts the
simulated time, so Foxglove's clock follows the run. :meth:`FoxgloveLiveWriter.wait_for_client`
holds the run until a client subscribes to a topic (messages published before are lost).

``foxglove-sdk`` is an optional extra (``pip install -e '.[foxglove]'``): without it
:func:`open_foxglove` raises an :class:`~orccad_app.diagnostics.OrccadError` saying what to
install (exit status 2).
"""

from __future__ import annotations

import threading
import time
from collections.abc import Mapping
from typing import Any

from orccad_app.diagnostics import OrccadError
from orccad_app.trace.mcap_writer import TopicWriter

__all__ = ["FoxgloveLiveWriter", "open_foxglove", "DEFAULT_PORT", "INSTALL_HINT"]

DEFAULT_PORT = 8765
"""Foxglove's usual WebSocket port."""

INSTALL_HINT = ("orccad run --foxglove needs the foxglove-sdk package: "
                "pip install -e '.[foxglove]' (or pip install foxglove-sdk)")

_TIME_STEP_NS = 10_000_000
"""The simulated time is broadcast at most every 10 ms of it."""

BACKLOG_MESSAGES = 65_536
"""Messages queued per client before the server drops the oldest (the SDK's default, 1024, is
a fraction of a second of a 1 kHz run's topics: a client slowed by a loaded machine lost
messages, the run's end among them)."""

DRAIN_S = 0.5
"""Wall time [s] the server stays up after the run's last message, so that the queued
messages reach the client before it closes."""


def _sdk() -> Any:
    try:
        import foxglove
        from foxglove.websocket import Capability  # noqa: F401 - the server's part
    except ImportError:
        raise OrccadError(INSTALL_HINT) from None
    return foxglove


class _LiveChannel:
    """A channel of the server; ``latched``: its id when it is a state topic."""

    __slots__ = ("channel", "latched")

    def __init__(self, channel: Any, latched: int | None) -> None:
        self.channel, self.latched = channel, latched


class FoxgloveLiveWriter(TopicWriter):
    """The trace's topics published on a Foxglove WebSocket server at ``host:port`` (``0``: a
    free port, see :attr:`port`); :meth:`close` stops the server."""

    def __init__(self, port: int = DEFAULT_PORT, metadata: Mapping[str, str] | None = None,
                 sensors: Mapping[tuple[str, str], str] | None = None, *,
                 host: str = "127.0.0.1") -> None:
        foxglove = _sdk()
        from foxglove.websocket import Capability, ServerListener

        subscribed = self._subscribed = threading.Event()
        self._latest: dict[int, tuple[Any, bytes, int]] = {}
        latest = self._latest

        class _Listener(ServerListener):
            def on_subscribe(self, client: Any, channel: Any) -> None:
                subscribed.set()
                last = latest.get(channel.id)  # a state topic's current value, at once
                if last is not None:
                    sent, body, time_ns = last
                    sent.log(body, log_time=time_ns)

        self._foxglove = foxglove
        self._context = foxglove.Context()
        name = "orccad " + " ".join(f"{k}={v}" for k, v in (metadata or {}).items())
        try:
            self._server = foxglove.start_server(name=name.strip(), host=host, port=port,
                                                 capabilities=[Capability.Time],
                                                 server_listener=_Listener(),
                                                 context=self._context,
                                                 message_backlog_size=BACKLOG_MESSAGES)
        except Exception as error:  # the SDK raises a RuntimeError with the OS's reason
            raise OrccadError(f"--foxglove-port {port}: cannot listen on {host}:{port}: "
                              f"{error}") from None
        self._time_ns = -_TIME_STEP_NS
        super().__init__(metadata, sensors)

    @property
    def port(self) -> int:
        """The port the server listens on."""
        return int(self._server.port)

    @property
    def url(self) -> str:
        """The WebSocket URL to open in Foxglove."""
        return f"ws://127.0.0.1:{self.port}"

    def wait_for_client(self, timeout_s: float) -> bool:
        """Block until a client subscribes to a topic, at most ``timeout_s`` [s] (wall
        time); whether one did. Ctrl-C interrupts the wait."""
        deadline = time.monotonic() + timeout_s
        while not self._subscribed.is_set():
            left = deadline - time.monotonic()
            if left <= 0:
                return False
            self._subscribed.wait(min(left, 0.1))
        return True

    def _register(self, topic: str, name: str, schema: str, latched: bool) -> Any:
        foxglove = self._foxglove
        channel = foxglove.Channel(topic, message_encoding="json", context=self._context,
                                   schema=foxglove.Schema(name=name, encoding="jsonschema",
                                                          data=schema.encode()))
        return _LiveChannel(channel, channel.id() if latched else None)

    def _publish(self, channel: Any, time_ns: int, body: bytes, sequence: int) -> None:
        if time_ns >= self._time_ns + _TIME_STEP_NS:
            self._time_ns = time_ns
            self._server.broadcast_time(time_ns)
        if channel.latched is not None:
            self._latest[channel.latched] = (channel.channel, body, time_ns)
        channel.channel.log(body, log_time=time_ns)

    def _finish(self) -> None:
        self._server.broadcast_time(max(self._time_ns, self._last_ns))
        if self._subscribed.is_set():
            time.sleep(DRAIN_S)
        self._server.stop()


def open_foxglove(port: int = DEFAULT_PORT, metadata: Mapping[str, str] | None = None,
                  sensors: Mapping[tuple[str, str], str] | None = None) -> FoxgloveLiveWriter:
    """A :class:`FoxgloveLiveWriter` listening on loopback at ``port``."""
    return FoxgloveLiveWriter(port, metadata, sensors)


def require_foxglove() -> None:
    """Raise the install hint now when ``foxglove-sdk`` is missing (before a run starts)."""
    _sdk()
