"""Ports: the only way Module-Tasks exchange values (RR-1801 §3.2.1).

A :class:`Port` belongs to a module (a :class:`~orccad_app.tcs.module_task.ModuleTask` or a
physical resource such as the plant) and is named ``module.port`` in the TCS. Data flows from
producer (``out``) ports to consumer (``in``) ports; a port of type ``event`` carries signals that
the executive also surfaces to its observers.

One port vocabulary: the direction is the control library's
:class:`~orccad_app.control.ports.PortDirection`, shared with the ports module kinds and robot
types declare (:class:`~orccad_app.control.ports.PortSpec`); a :class:`Port` is such a port
placed in a TCS, with the value read before any write (the mission layer converts one into the
other, :func:`orccad_app.mission.tcs_bridge.tcs_port`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from orccad_app.control.ports import PortDirection
from orccad_app.diagnostics import OrccadError

__all__ = ["PortDirection", "Port", "PortRef", "EVENT", "NUMERIC_TYPES"]

EVENT = "event"
"""Type name of event ports: a value that is not ``None``/``False`` is a signal occurrence."""

NUMERIC_TYPES = frozenset({"float", "int", "bool"})
"""Types whose default initial value is zero (a scalar if ``dim == 1``, else a vector)."""


@dataclass(frozen=True, slots=True)
class Port:
    """A typed port of a module.

    :param name: identifier, unique within its module.
    :param direction: ``"in"`` (consumer) or ``"out"`` (producer).
    :param type: value type name (``float``, ``int``, ``bool``, ``event`` or any
        plugin-defined name); connected ports must agree on it.
    :param dim: number of components (a vector of ``dim`` values); connected ports must agree.
    :param initial: value read before any write arrives; ``None`` means zero for numeric
        types (scalar if ``dim == 1``) and ``None`` otherwise.
    """

    name: str
    direction: PortDirection
    type: str = "float"
    dim: int = 1
    initial: Any = None

    def __post_init__(self) -> None:
        if not self.name or not self.name.isidentifier():
            raise OrccadError(f"invalid port name {self.name!r}: expected an identifier")
        try:
            object.__setattr__(self, "direction", PortDirection(self.direction))
        except ValueError:
            raise OrccadError(f"port '{self.name}': direction must be 'in' or 'out', "
                              f"got {self.direction!r}") from None
        if not isinstance(self.dim, int) or self.dim < 1:
            raise OrccadError(f"port '{self.name}': dim must be a positive integer, "
                              f"got {self.dim!r}")

    @property
    def is_event(self) -> bool:
        """Whether this port carries signals (type ``event``)."""
        return self.type == EVENT

    def initial_value(self) -> Any:
        """The value a reader gets before the first write: ``initial`` or a typed zero."""
        if self.initial is not None or self.type not in NUMERIC_TYPES:
            return self.initial
        if self.dim == 1:
            return 0.0 if self.type == "float" else 0
        import numpy as np

        return np.zeros(self.dim, dtype=float if self.type == "float" else int)


@dataclass(frozen=True, order=True, slots=True)
class PortRef:
    """One end of a connection, or an observer's event port: port ``port`` of module
    ``module`` (a TCS module name may hold dots, ``Task.module``; a port name does not).
    ``str()`` is the TCS's name of the port, ``module.port``."""

    module: str
    port: str

    def __str__(self) -> str:
        return f"{self.module}.{self.port}"

    @classmethod
    def parse(cls, ref: str) -> PortRef:
        """The reference named ``"module.port"`` (its last dot splits); raise on a malformed
        one. Only where a reference enters the TCS as text (the plan language, the API)."""
        module, dot, port = ref.rpartition(".")
        if not dot or not module or not port:
            raise OrccadError(f"bad port reference {ref!r}: expected 'module.port'")
        return cls(module, port)

