"""Connections: one producer port to one consumer port under one protocol (RR-1801 §3.2.1)."""

from __future__ import annotations

from dataclasses import dataclass, field

from orccad_app.diagnostics import SourceLocation
from orccad_app.tcs.port import PortRef
from orccad_app.tcs.protocol import Protocol, parse_protocol

__all__ = ["Connection"]


@dataclass(frozen=True, slots=True)
class Connection:
    """A directed, typed data transfer ``producer -> consumer``.

    :param producer: ``"module.port"`` of an output port.
    :param consumer: ``"module.port"`` of an input port.
    :param protocol: one of the 8 protocol names (or a :class:`Protocol`).
    :param location: where the plan language declared it, for diagnostics.

    ``source`` and ``target`` are the two ends as :class:`~orccad_app.tcs.port.PortRef`
    (parsed once, here).
    """

    producer: str
    consumer: str
    protocol: Protocol = Protocol.ASYN_ASYN
    location: SourceLocation | None = field(default=None, compare=False)
    source: PortRef = field(init=False, compare=False, repr=False)
    target: PortRef = field(init=False, compare=False, repr=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "protocol", parse_protocol(self.protocol))
        object.__setattr__(self, "source", PortRef.parse(self.producer))
        object.__setattr__(self, "target", PortRef.parse(self.consumer))

    @property
    def producer_module(self) -> str:
        return self.source.module

    @property
    def producer_port(self) -> str:
        return self.source.port

    @property
    def consumer_module(self) -> str:
        return self.target.module

    @property
    def consumer_port(self) -> str:
        return self.target.port

    @property
    def label(self) -> str:
        """``producer -> consumer (protocol)``, for messages and traces."""
        return f"{self.producer} -> {self.consumer} ({self.protocol.value})"

    def __str__(self) -> str:
        return self.label
