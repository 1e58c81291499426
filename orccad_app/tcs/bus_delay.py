"""The bus in the timing analysis: message classes and their worst delays.

A connection between Module-Tasks on different processors puts messages on the executive's
FIFO bus (:mod:`orccad_app.executive.bus`): one *data* message per producer job for the push
protocols, a *request* and a *reply* per consumer job for the pull ones (``synD``,
``synDF``). A message class is sent at most once per period of the Module-Task whose job sends
it, anywhere between that job's release and its response bound (its jitter).

On a FIFO bus a message is delivered within the busy period it is sent in, so every message's
delay (queueing + its own transfer) is bounded by the longest busy period

.. math::

    L = \\sum_m \\lceil (L + J_m) / T_m \\rceil \\, c_m

(``c_m`` the transfer time of class ``m``), which exists when the bus utilization
:math:`\\sum c_m / T_m` is below 1. The queueing delay of a class is ``L - c_m``.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Mapping

from orccad_app.tcs.processor_demand import BudgetExceeded, Load, busy_period_ns

if TYPE_CHECKING:
    from orccad_app.tcs.graph import TCS

__all__ = ["BusModel", "MessageClass", "message_classes", "bus_delays"]


@dataclass(frozen=True, slots=True)
class BusModel:
    """The bus's transfer times, as the executive's :class:`~orccad_app.executive.bus.Bus`.

    :param transfer_ns: time a data or reply message occupies the bus [ns].
    :param request_ns: time a request occupies it [ns]; defaults to ``transfer_ns``.
    """

    transfer_ns: int = 0
    request_ns: int | None = None

    @property
    def request_time_ns(self) -> int:
        return self.transfer_ns if self.request_ns is None else self.request_ns


@dataclass(frozen=True, slots=True)
class MessageClass:
    """One kind of message of one connection.

    :param connection: the connection's label.
    :param kind: ``data``, ``request`` or ``reply``.
    :param sender: the Module-Task whose jobs send it.
    :param period_ns: shortest time between two messages of the class [ns].
    :param transfer_ns: its transfer time [ns].
    :param bus_utilization: the whole bus's utilization.
    :param delay_ns: worst delay, queueing and transfer [ns]; ``None`` when unbounded or not
        computed.
    """

    connection: str
    kind: str
    sender: str
    period_ns: int
    transfer_ns: int
    bus_utilization: float = 0.0
    delay_ns: int | None = None

    @property
    def queueing_ns(self) -> int | None:
        """Worst time waiting for the bus [ns]."""
        return None if self.delay_ns is None else self.delay_ns - self.transfer_ns

    @property
    def rate_hz(self) -> float:
        return 1e9 / self.period_ns

    def with_delay(self, delay_ns: int | None) -> MessageClass:
        return replace(self, delay_ns=delay_ns)


def message_classes(tcs: TCS, bus: BusModel) -> list[MessageClass]:
    """The message classes of ``tcs``'s connections that cross the bus, in connection order."""
    tasks = {t.name: t for t in tcs.module_tasks}
    classes: list[MessageClass] = []
    for c in tcs.connections:
        producer, consumer = tasks.get(c.producer_module), tasks.get(c.consumer_module)
        if producer is None or consumer is None or producer.processor == consumer.processor:
            continue
        if c.protocol.is_pull:
            period = consumer.min_interarrival_ns
            classes.append(MessageClass(c.label, "request", consumer.name, period,
                                        bus.request_time_ns))
            classes.append(MessageClass(c.label, "reply", consumer.name, period,
                                        bus.transfer_ns))
        else:
            classes.append(MessageClass(c.label, "data", producer.name,
                                        producer.min_interarrival_ns, bus.transfer_ns))
    load = sum(m.transfer_ns / m.period_ns for m in classes)
    return [replace(m, bus_utilization=load) for m in classes]


def bus_delays(classes: list[MessageClass], response_ns: Mapping[str, int],
               limit_ns: int) -> dict[tuple[str, str], int] | None:
    """(connection label, kind) -> worst delay [ns]; ``None`` when the bus is overloaded
    (no busy period under ``limit_ns``). ``response_ns`` bounds when a sender's job sends."""
    if not classes:
        return {}
    loads = [Load(m.connection, m.transfer_ns, m.period_ns, m.period_ns,
                  response_ns[m.sender], 1) for m in classes]
    try:
        busy = busy_period_ns(loads, limit_ns)
    except BudgetExceeded:
        return None
    if busy is None:
        return None
    return {(m.connection, m.kind): busy for m in classes}
