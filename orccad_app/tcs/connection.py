"""Connections: one producer port to one consumer port under one protocol (RR-1801 §3.2.1)."""

from __future__ import annotations

from dataclasses import dataclass, field

from orccad_app.diagnostics import SourceLocation
from orccad_app.tcs.port import split_port_ref
from orccad_app.tcs.protocol import Protocol, parse_protocol

__all__ = ["Connection"]


@dataclass(frozen=True, slots=True)
class Connection:
    """A directed, typed data transfer ``producer -> consumer``.

    :param producer: ``"module.port"`` of an output port.
    :param consumer: ``"module.port"`` of an input port.
    :param protocol: one of the 8 protocol names (or a :class:`Protocol`).
    :param location: where the plan language declared it, for diagnostics.
    """

    producer: str
    consumer: str
    protocol: Protocol = Protocol.ASYN_ASYN
    location: SourceLocation | None = field(default=None, compare=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "protocol", parse_protocol(self.protocol))
        split_port_ref(self.producer)
        split_port_ref(self.consumer)

    @property
    def producer_module(self) -> str:
        return split_port_ref(self.producer)[0]

    @property
    def producer_port(self) -> str:
        return split_port_ref(self.producer)[1]

    @property
    def consumer_module(self) -> str:
        return split_port_ref(self.consumer)[0]

    @property
    def consumer_port(self) -> str:
        return split_port_ref(self.consumer)[1]

    @property
    def label(self) -> str:
        """``producer -> consumer (protocol)``, for messages and traces."""
        return f"{self.producer} -> {self.consumer} ({self.protocol.value})"

    def __str__(self) -> str:
        return self.label
