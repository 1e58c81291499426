"""Zenoh endpoints as ``--ros2-zenoh`` takes them: ``<protocol>/<address>[?<metadata>]``.

:func:`check_endpoint` refuses, before anything is loaded, what Zenoh could never connect
to: an unknown protocol, an address without a port where one is needed, a port that is not a
whole number in ``[1, 65535]``. :func:`zenoh_reason` keeps of Zenoh's own error its message,
without the Rust source paths it carries. No Zenoh here (plain strings).
"""

from __future__ import annotations

import re

from orccad_app.diagnostics import OrccadError

__all__ = ["check_endpoint", "zenoh_reason", "PROTOCOLS", "PORT_PROTOCOLS"]

PORT_PROTOCOLS = ("tcp", "udp", "tls", "quic", "ws")
"""Zenoh's protocols whose address is ``host:port``."""
PROTOCOLS = PORT_PROTOCOLS + ("unixsock-stream", "unixpipe", "serial", "vsock")
"""Every protocol Zenoh's endpoints may name."""


def check_endpoint(text: str, option: str = "--ros2-zenoh") -> str:
    """``text`` if it is an endpoint Zenoh can connect to, else a located
    :class:`OrccadError` naming ``option`` and what is wrong."""
    def refuse(why: str) -> OrccadError:
        return OrccadError(f"{option} {text}: {why} (an endpoint is PROTOCOL/HOST:PORT, "
                           "e.g. tcp/127.0.0.1:7447)")

    protocol, slash, address = text.partition("/")
    address = re.split(r"[?#]", address, maxsplit=1)[0]
    if not slash or not protocol or not address:
        raise refuse("not an endpoint")
    if protocol not in PROTOCOLS:
        raise refuse(f"unknown protocol {protocol!r} (Zenoh's are {', '.join(PROTOCOLS)})")
    if protocol not in PORT_PROTOCOLS:
        return text
    host, colon, port = address.rpartition(":")
    if not colon:
        raise refuse("the address has no port")
    if not host or host == "[]":
        raise refuse("the address has no host")
    if not port.isdigit() or not 1 <= int(port) <= 65535:
        raise refuse(f"the port must be a whole number in [1, 65535], not {port!r}")
    return text


def zenoh_reason(error: BaseException) -> str:
    """Zenoh's message in ``error``, without the Rust source paths (`` at /…/x.rs:12.``) and
    the JSON5 wrapping; at most 200 characters."""
    text = str(error)
    found = re.search(r'msg: "(.*?)"(?:, location|\s*\})', text)
    if found is not None:
        text = found.group(1)
    text = re.sub(r"\s*at /\S+\.rs:\d+\.?", "", text).strip().rstrip(".:")
    return text if len(text) <= 200 else text[:197] + "..."
