"""The 8 synchronization protocols of a connection (RR-1801 §3.2.1, docs/design.md).

A protocol is named ``producer_end/consumer_end``; its ends say who may block:

==============  ====================================  ======================================
protocol        producer write                        consumer read
==============  ====================================  ======================================
``asyn/asyn``   never blocks, overwrites              never blocks, last value (may be stale)
``syn/syn``     rendez-vous: waits for a read         rendez-vous: waits for a write
``asyn/syn``    never blocks                          fresh value at once, else next write
``syn/asyn``    waits unless read since last write    never blocks
``asyn/synF``   never blocks                          always waits for the next write
``synF/asyn``   always waits for the next read        never blocks
``asyn/synD``   never blocks, no bus traffic          request, waits for the latest value
``asyn/synDF``  never blocks                          request, waits for the next write
==============  ====================================  ======================================

Values: a read is a *demand*, a write a *supply*. A consumer released by a write (``syn/syn``,
``asyn/syn``, ``asyn/synF``, ``asyn/synDF``) gets that write's value. A consumer that never
blocks cannot wait for a value: it reads what has been delivered so far, and a producer blocked
on ``syn/asyn`` or ``synF/asyn`` commits its value just after the read that releases it (so
``syn/asyn`` never overwrites an unread value). Bus traffic between processors: one message per
write (per transfer for ``syn/syn``); a request and a reply per read for ``synD``/``synDF``
(the pull variants save bus load when the consumer is slower than the producer).
"""

from __future__ import annotations

from enum import Enum

from orccad_app.diagnostics import OrccadError

__all__ = ["Protocol", "parse_protocol"]


class Protocol(str, Enum):
    """One of the 8 port-pair protocols; the value is its name in the plan language."""

    ASYN_ASYN = "asyn/asyn"
    """Both ends run freely; the consumer reads the last value."""
    SYN_SYN = "syn/syn"
    """Classical rendez-vous: the first end to arrive waits for the other."""
    ASYN_SYN = "asyn/syn"
    """The consumer waits for the next write unless a value arrived since its last read."""
    SYN_ASYN = "syn/asyn"
    """The producer waits for the next read unless a read happened since its last write."""
    ASYN_SYNF = "asyn/synF"
    """The consumer always waits for the next write."""
    SYNF_ASYN = "synF/asyn"
    """The producer always waits for the next read."""
    ASYN_SYND = "asyn/synD"
    """Pull: the consumer requests and waits for the producer side's latest value."""
    ASYN_SYNDF = "asyn/synDF"
    """Pull: the consumer requests and waits for the producer's next write after the request."""

    @property
    def producer_end(self) -> str:
        """``asyn``, ``syn`` or ``synF``."""
        return self.value.split("/")[0]

    @property
    def consumer_end(self) -> str:
        """``asyn``, ``syn``, ``synF``, ``synD`` or ``synDF``."""
        return self.value.split("/")[1]

    @property
    def producer_may_block(self) -> bool:
        """Whether a write can wait for the consumer."""
        return self.producer_end != "asyn"

    @property
    def consumer_may_block(self) -> bool:
        """Whether a read can wait (for the producer or for the bus)."""
        return self.consumer_end != "asyn"

    @property
    def consumer_waits_for_producer(self) -> bool:
        """Whether a blocked read can only be released by the producer module (not the bus)."""
        return self.consumer_end in ("syn", "synF", "synDF")

    @property
    def is_pull(self) -> bool:
        """Whether reads are requests answered over the bus (the D variants)."""
        return self.consumer_end in ("synD", "synDF")


def parse_protocol(name: str | Protocol) -> Protocol:
    """The :class:`Protocol` named ``name``; raise :class:`OrccadError` naming a bad one."""
    if isinstance(name, Protocol):
        return name
    try:
        return Protocol(name)
    except ValueError:
        known = ", ".join(p.value for p in Protocol)
        raise OrccadError(f"unknown protocol {name!r}: expected one of {known}") from None
