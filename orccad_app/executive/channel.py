"""Run-time channels: one per connection, implementing its protocol (docs/design.md, the protocols table).

A channel's state lives on the consumer side. Between Module-Tasks on different processors a
value crosses the bus (:mod:`orccad_app.executive.bus`): it becomes visible to the consumer when
its message is delivered. Control signalling (a read releasing a blocked producer) is not a bus
message, matching the table's traffic column: push protocols send one message per write (per
transfer for ``syn/syn``), pull protocols a request and a reply per read.

**Fresh ports.** :meth:`Channel.reset` brings a channel back to its state before any write
(its initial value, no pending reader, writer or request) and discards the values still
crossing the bus: a Robot-Task run again starts with fresh ports as well as fresh modules, so
it never reads what its previous instance wrote (docs/executive.md, *What runs*).

``read(job)`` returns the value or :data:`~orccad_app.executive.block.BLOCK`;
``write(job, value)`` returns ``True`` when done, ``False`` when blocked. A blocked job is
released through ``job.runtime.wake(job, value)``; the channel sets ``job.waits_for`` to the
Module-Task that alone can release it (for dynamic deadlock detection).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Callable

from orccad_app.executive.block import BLOCK
from orccad_app.tcs.connection import Connection
from orccad_app.tcs.protocol import Protocol

if TYPE_CHECKING:
    from orccad_app.executive.bus import Bus
    from orccad_app.executive.delays import PortExchange
    from orccad_app.executive.job import Job, JobOwner

__all__ = ["Channel", "make_channel", "SensorChannel", "ActuatorChannel"]


class Channel:
    """Common state of a connection at run time.

    :param connection: the TCS connection.
    :param producer: run-time of the producing Module-Task.
    :param consumer: run-time of the consuming Module-Task.
    :param initial: the value read before any write.
    :param bus: the bus crossed between different processors, ``None`` on one processor.
    """

    __slots__ = ("connection", "label", "protocol_name", "producer", "consumer", "bus", "value",
                 "writes", "reads", "initial", "epoch")

    def __init__(self, connection: Connection, producer: JobOwner | None,
                 consumer: JobOwner | None, initial: Any, bus: Bus | None) -> None:
        self.connection = connection
        self.label = connection.label
        self.protocol_name = connection.protocol.value
        self.producer = producer
        self.consumer = consumer
        self.bus = bus
        self.value = initial
        self.initial = initial
        self.epoch = 0
        self.writes = 0
        self.reads = 0

    def reset(self) -> None:
        """Back to the state before any write; values in flight on the bus are dropped."""
        self.value = self.initial
        self.epoch += 1

    def _send(self, kind: str, payload: Any, then: Callable[[Any], None]) -> None:
        if self.bus is None:
            then(payload)
        else:
            self.bus.send(kind, self.label, payload, self._current(then))

    def _current(self, then: Callable[[Any], None]) -> Callable[[Any], None]:
        """``then``, unless the channel was reset before the message is delivered."""
        epoch = self.epoch

        def deliver(payload: Any) -> None:
            if self.epoch == epoch:
                then(payload)
        return deliver

    def _store(self, value: Any) -> None:
        self.value = value

    def read(self, job: Job) -> Any:
        raise NotImplementedError

    def write(self, job: Job, value: Any) -> bool:
        raise NotImplementedError

    def cancel(self, job: Job) -> None:
        """Forget ``job`` (killed) if it is waiting here."""


class AsynAsyn(Channel):
    """Neither end blocks; the consumer reads the last delivered value."""

    __slots__ = ()

    def write(self, job: Job, value: Any) -> bool:
        self.writes += 1
        if self.bus is None:  # _send's own-processor case, without its two calls
            self.value = value
        else:
            self._send("data", value, self._store)
        return True

    def read(self, job: Job) -> Any:
        self.reads += 1
        return self.value


class AsynSyn(Channel):
    """The consumer takes a fresh value at once, else waits for the next delivery."""

    __slots__ = ("fresh", "reader")

    def __init__(self, *args: Any) -> None:
        super().__init__(*args)
        self.fresh = False
        self.reader: Job | None = None

    def reset(self) -> None:
        super().reset()
        self.fresh = False
        self.reader = None

    def write(self, job: Job, value: Any) -> bool:
        self.writes += 1
        self._send("data", value, self._arrive)
        return True

    def _arrive(self, value: Any) -> None:
        self.value = value
        reader = self.reader
        if reader is None:
            self.fresh = True
        else:
            self.reader = None
            reader.runtime.wake(reader, value)

    def read(self, job: Job) -> Any:
        self.reads += 1
        if self.fresh:
            self.fresh = False
            return self.value
        self.reader = job
        job.waits_for = self.producer
        return BLOCK

    def cancel(self, job: Job) -> None:
        if self.reader is job:
            self.reader = None


class AsynSynF(AsynSyn):
    """The consumer always waits for the next delivery."""

    __slots__ = ()

    def _arrive(self, value: Any) -> None:
        self.value = value
        reader = self.reader
        if reader is not None:
            self.reader = None
            reader.runtime.wake(reader, value)

    def read(self, job: Job) -> Any:
        self.reads += 1
        self.reader = job
        job.waits_for = self.producer
        return BLOCK


class SynAsyn(Channel):
    """The producer writes at once if a read happened since its last write, else it waits for
    the next read and commits its value just after it."""

    __slots__ = ("demand", "writer", "pending")

    def __init__(self, *args: Any) -> None:
        super().__init__(*args)
        self.demand = True
        self.writer: Job | None = None
        self.pending: Any = None

    def reset(self) -> None:
        super().reset()
        self.demand = True
        self.writer = None
        self.pending = None

    def write(self, job: Job, value: Any) -> bool:
        self.writes += 1
        if self.demand:
            self.demand = False
            self._send("data", value, self._store)
            return True
        self.writer = job
        self.pending = value
        job.waits_for = self.consumer
        return False

    def read(self, job: Job) -> Any:
        self.reads += 1
        value = self.value
        writer = self.writer
        if writer is None:
            self.demand = True
        else:
            self.writer = None
            self._send("data", self.pending, self._store)
            self.pending = None
            writer.runtime.wake(writer)
        return value

    def cancel(self, job: Job) -> None:
        if self.writer is job:
            self.writer = None
            self.pending = None


class SynFAsyn(SynAsyn):
    """The producer always waits for the next read and commits its value just after it."""

    __slots__ = ()

    def write(self, job: Job, value: Any) -> bool:
        self.writes += 1
        self.writer = job
        self.pending = value
        job.waits_for = self.consumer
        return False

    def read(self, job: Job) -> Any:
        self.reads += 1
        value = self.value
        writer = self.writer
        if writer is not None:
            self.writer = None
            self._send("data", self.pending, self._store)
            self.pending = None
            writer.runtime.wake(writer)
        return value


class SynSyn(Channel):
    """Rendez-vous: the first end to arrive waits; the value crosses when both are there, and
    both go on when it is delivered."""

    __slots__ = ("reader", "writer", "pending")

    def __init__(self, *args: Any) -> None:
        super().__init__(*args)
        self.reader: Job | None = None
        self.writer: Job | None = None
        self.pending: Any = None

    def reset(self) -> None:
        super().reset()
        self.reader = None
        self.writer = None
        self.pending = None

    def write(self, job: Job, value: Any) -> bool:
        self.writes += 1
        reader = self.reader
        if reader is None:
            self.writer = job
            self.pending = value
            job.waits_for = self.consumer
            return False
        self.reader = None
        if self.bus is None:
            self.value = value
            reader.runtime.wake(reader, value)
            return True
        job.waits_for = None
        self.bus.send("data", self.label, (value, reader, job), self._current(self._meet))
        return False

    def read(self, job: Job) -> Any:
        self.reads += 1
        writer = self.writer
        if writer is None:
            self.reader = job
            job.waits_for = self.producer
            return BLOCK
        self.writer = None
        value, self.pending = self.pending, None
        if self.bus is None:
            self.value = value
            writer.runtime.wake(writer)
            return value
        job.waits_for = None
        self.bus.send("data", self.label, (value, job, writer), self._current(self._meet))
        return BLOCK

    def _meet(self, payload: tuple) -> None:
        value, reader, writer = payload
        self.value = value
        reader.runtime.wake(reader, value)
        writer.runtime.wake(writer)

    def cancel(self, job: Job) -> None:
        if self.reader is job:
            self.reader = None
        if self.writer is job:
            self.writer = None
            self.pending = None


class AsynSynD(Channel):
    """Pull: a read sends a request; the producer side answers with its latest value."""

    __slots__ = ()

    def write(self, job: Job, value: Any) -> bool:
        self.writes += 1
        self.value = value
        return True

    def read(self, job: Job) -> Any:
        self.reads += 1
        if self.bus is None:
            return self.value
        job.waits_for = None
        self.bus.send("request", self.label, job, self._answer)
        return BLOCK

    def _answer(self, job: Job) -> None:
        assert self.bus is not None  # only ever called back by the bus
        self.bus.send("reply", self.label, (self.value, job), self._reply)

    @staticmethod
    def _reply(payload: tuple) -> None:
        value, job = payload
        job.runtime.wake(job, value)


class AsynSynDF(Channel):
    """Pull: a read sends a request; the producer side answers with the first value written
    after the request arrived."""

    __slots__ = ("requester", "arrived")

    def __init__(self, *args: Any) -> None:
        super().__init__(*args)
        self.requester: Job | None = None
        self.arrived = False

    def reset(self) -> None:
        super().reset()
        self.requester = None
        self.arrived = False

    def write(self, job: Job, value: Any) -> bool:
        self.writes += 1
        self.value = value
        requester = self.requester
        if requester is not None and self.arrived:
            self.requester = None
            if self.bus is None:
                requester.runtime.wake(requester, value)
            else:
                self.bus.send("reply", self.label, (value, requester), AsynSynD._reply)
        return True

    def read(self, job: Job) -> Any:
        self.reads += 1
        self.requester = job
        if self.bus is None:
            self.arrived = True
            job.waits_for = self.producer
        else:
            self.arrived = False
            job.waits_for = None
            self.bus.send("request", self.label, job, self._arrive)
        return BLOCK

    def _arrive(self, job: Job) -> None:
        if self.requester is job:
            self.arrived = True
            job.waits_for = self.producer
            job.runtime.check_deadlock(job)

    def cancel(self, job: Job) -> None:
        if self.requester is job:
            self.requester = None


class SensorChannel(Channel):
    """A plant sensor feeding a Module-Task input: sampled at the instant of the read, or
    at the last exchange of a :class:`~orccad_app.executive.delays.PortExchange`."""

    __slots__ = ("plant", "port", "exchange")

    def __init__(self, connection: Connection, consumer: JobOwner | None, plant: Any) -> None:
        super().__init__(connection, None, consumer, None, None)
        self.plant = plant
        self.port = connection.producer_port
        self.exchange: PortExchange | None = None

    def read(self, job: Job) -> Any:
        self.reads += 1
        if self.exchange is not None:
            return self.exchange.sensor(self.plant, self.port)
        return self.plant.sample(self.port)


class ActuatorChannel(Channel):
    """A Module-Task output driving a plant actuator: held until the next write (applied at
    once, or at the next exchange of a :class:`~orccad_app.executive.delays.PortExchange`)."""

    __slots__ = ("plant", "port", "exchange")

    def __init__(self, connection: Connection, producer: JobOwner, plant: Any) -> None:
        super().__init__(connection, producer, None, None, None)
        self.plant = plant
        self.port = connection.consumer_port
        self.exchange: PortExchange | None = None

    def write(self, job: Job, value: Any) -> bool:
        self.writes += 1
        if self.exchange is not None:
            self.exchange.actuate(self.plant, self.port, value, self.producer)
        else:
            self.plant.actuate(self.port, value)
        return True


_CLASSES: dict[Protocol, type[Channel]] = {
    Protocol.ASYN_ASYN: AsynAsyn,
    Protocol.SYN_SYN: SynSyn,
    Protocol.ASYN_SYN: AsynSyn,
    Protocol.SYN_ASYN: SynAsyn,
    Protocol.ASYN_SYNF: AsynSynF,
    Protocol.SYNF_ASYN: SynFAsyn,
    Protocol.ASYN_SYND: AsynSynD,
    Protocol.ASYN_SYNDF: AsynSynDF,
}


def make_channel(connection: Connection, producer: JobOwner, consumer: JobOwner,
                 initial: Any, bus: Bus | None) -> Channel:
    """The channel class of ``connection.protocol``, built."""
    return _CLASSES[connection.protocol](connection, producer, consumer, initial, bus)
