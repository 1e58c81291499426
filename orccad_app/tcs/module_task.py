"""Module-Tasks and physical resources: the nodes of the TCS graph (RR-1801 §3.2, §3.3).

A :class:`ModuleTask` is a periodic real-time task ``init; loop { read all inputs; compute;
write all outputs }`` with temporal attributes (period, execution time, processor, priority).
Its behaviour is a *compute object*, duck-typed:

- ``compute(t_s: float, inputs: dict) -> dict`` — called once per job at the start of its
  compute phase with the simulated time in [s] and the values read on the input ports; returns
  the values to write on output ports (a port missing from the dict is not written this job);
- ``init()`` *(optional)* — called when the Module-Task is activated;
- ``set_param(name, value)`` *(optional)* — called for a type-1 exception (``adjust``).

A :class:`PhysicalResource` is a pseudo module (the paper's ``PR.MAN`` box): a robot's sensors
are its producer ports, its actuators its consumer ports. It has no period: its sensors are
sampled when read.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from orccad_app.diagnostics import OrccadError, SourceLocation
from orccad_app.tcs.phasing import Activation
from orccad_app.tcs.port import PortDirection, Port

__all__ = ["ModuleTask", "PhysicalResource", "Activation"]


def _check_ports(owner: str, ports: tuple[Port, ...]) -> dict[str, Port]:
    by_name: dict[str, Port] = {}
    for port in ports:
        if not isinstance(port, Port):
            raise OrccadError(f"module '{owner}': ports must be Port objects, got {port!r}")
        if port.name in by_name:
            raise OrccadError(f"module '{owner}': duplicate port name '{port.name}'")
        by_name[port.name] = port
    return by_name


def _is_module_name(name: Any) -> bool:
    """An identifier, or identifiers joined by dots (``TrackPID.ctrl`` in a mission's TCS)."""
    return isinstance(name, str) and all(part.isidentifier() for part in name.split("."))


class _HasPorts:
    """Port look-up shared by Module-Tasks and physical resources."""

    name: str
    ports: tuple[Port, ...]
    _by_name: dict[str, Port]

    def port(self, name: str) -> Port:
        """The port called ``name``; raise :class:`OrccadError` listing the known ones."""
        try:
            return self._by_name[name]
        except KeyError:
            known = ", ".join(self._by_name) or "none"
            raise OrccadError(f"unknown port '{self.name}.{name}' "
                              f"(module '{self.name}' has ports: {known})") from None

    @property
    def inputs(self) -> tuple[Port, ...]:
        """Consumer ports, in declaration order (the order of reads)."""
        return tuple(p for p in self.ports if p.direction is PortDirection.IN)

    @property
    def outputs(self) -> tuple[Port, ...]:
        """Producer ports, in declaration order (the order of writes)."""
        return tuple(p for p in self.ports if p.direction is PortDirection.OUT)


@dataclass(eq=False)
class ModuleTask(_HasPorts):
    """A periodic Module-Task.

    :param name: identifier (or dotted identifiers, ``TrackPID.ctrl``), unique in the TCS.
    :param period_ns: activation period [ns], > 0.
    :param wcet_ns: worst-case execution time [ns], >= 0.
    :param compute: the compute object (see the module docstring).
    :param ports: the ports, inputs read and outputs written in declaration order.
    :param processor: name of the processor it runs on.
    :param priority: fixed priority, 1 is the highest.
    :param bcet_ns: best-case execution time [ns]; when given, each job's duration is drawn
        uniformly in ``[bcet_ns, wcet_ns]`` from the run's seed; else every job takes ``wcet_ns``.
    :param deadline_ns: relative deadline [ns]; 0 (the default): the period.
    :param offset_ns: delay of the first release after activation [ns].
    :param kind: the module kind (plugin name), informative.
    :param activation: :attr:`Activation.PERIODIC` (released every ``period_ns``) or
        :attr:`Activation.SPORADIC` (released by an event, interrupt-driven: then ``period_ns``
        is its minimum inter-arrival time, see :attr:`min_interarrival_ns`). The
        schedulability analysis handles both; the executive releases periodic ones.
    :param location: where the plan language declared it, for diagnostics.
    """

    name: str
    period_ns: int
    wcet_ns: int
    compute: Any = None
    ports: tuple[Port, ...] = ()
    processor: str = "cpu0"
    priority: int = 1
    bcet_ns: int | None = None
    deadline_ns: int = 0
    offset_ns: int = 0
    kind: str = ""
    location: SourceLocation | None = None
    activation: Activation = Activation.PERIODIC
    _by_name: dict[str, Port] = field(init=False, repr=False)

    def __post_init__(self) -> None:
        if not _is_module_name(self.name):
            raise OrccadError(f"invalid module-task name {self.name!r}: expected an identifier "
                              f"or dotted identifiers (Task.module)")
        self.ports = tuple(self.ports)
        self._by_name = _check_ports(self.name, self.ports)
        self._check_times()
        try:
            self.activation = Activation(self.activation)
        except ValueError:
            raise OrccadError(f"module-task '{self.name}': activation must be 'periodic' or "
                              f"'sporadic', got {self.activation!r}") from None
        if not isinstance(self.priority, int) or self.priority < 1:
            raise OrccadError(f"module-task '{self.name}': priority must be an integer >= 1 "
                              f"(1 is the highest), got {self.priority!r}")
        if self.compute is not None and not callable(getattr(self.compute, "compute", None)):
            raise OrccadError(f"module-task '{self.name}': compute object {self.compute!r} "
                              f"has no compute(t_s, inputs) method")

    def _check_times(self) -> None:
        def positive_int(label: str, value: Any, strict: bool) -> None:
            if not isinstance(value, int) or value < (1 if strict else 0):
                bound = "> 0" if strict else ">= 0"
                raise OrccadError(f"module-task '{self.name}': {label} must be an integer "
                                  f"number of ns {bound}, got {value!r}")

        positive_int("period_ns", self.period_ns, True)
        positive_int("wcet_ns", self.wcet_ns, False)
        positive_int("offset_ns", self.offset_ns, False)
        if self.bcet_ns is not None:
            positive_int("bcet_ns", self.bcet_ns, False)
            if self.bcet_ns > self.wcet_ns:
                raise OrccadError(f"module-task '{self.name}': bcet_ns {self.bcet_ns} exceeds "
                                  f"wcet_ns {self.wcet_ns}")
        if not self.deadline_ns:  # 0 (or None): the period
            self.deadline_ns = self.period_ns
        positive_int("deadline_ns", self.deadline_ns, True)

    @property
    def min_interarrival_ns(self) -> int:
        """The shortest time between two releases [ns]: the period of a periodic Module-Task,
        the minimum inter-arrival time of a sporadic one."""
        return self.period_ns

    @property
    def utilization(self) -> float:
        """``wcet_ns / period_ns``."""
        return self.wcet_ns / self.period_ns


@dataclass(eq=False)
class PhysicalResource(_HasPorts):
    """A pseudo module standing for the robot: sensors are ``out`` ports, actuators ``in``.

    :param name: identifier, unique in the TCS (e.g. ``arm``).
    :param ports: sensor (producer) and actuator (consumer) ports.
    """

    name: str
    ports: tuple[Port, ...] = ()
    _by_name: dict[str, Port] = field(init=False, repr=False)

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name.isidentifier():
            raise OrccadError(f"invalid resource name {self.name!r}: expected an identifier")
        self.ports = tuple(self.ports)
        self._by_name = _check_ports(self.name, self.ports)

    @staticmethod
    def sensor(name: str, dim: int = 1, type: str = "float") -> Port:
        """A sensor port (producer, sampled when read)."""
        return Port(name, PortDirection.OUT, type, dim)

    @staticmethod
    def actuator(name: str, dim: int = 1, type: str = "float") -> Port:
        """An actuator port (consumer, held until the next write)."""
        return Port(name, PortDirection.IN, type, dim)
