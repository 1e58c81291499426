"""The TCS graph of a Robot-Task: Module-Tasks, resources and connections (RR-1801 §3.3.2).

Nodes are module names (attribute ``module``: the :class:`ModuleTask` or
:class:`PhysicalResource`); each edge is one :class:`Connection` (attribute ``connection``).
Coherence is checked as connections are added (unknown names, direction, type and dimension,
an input fed twice) and by :meth:`TCS.check` (every input fed, resources wired ``asyn/asyn``).
"""

from __future__ import annotations

from typing import Iterable

import networkx as nx

from orccad_app.diagnostics import OrccadError, SourceLocation
from orccad_app.tcs.connection import Connection
from orccad_app.tcs.module_task import ModuleTask, PhysicalResource
from orccad_app.tcs.port import PortDirection, Port
from orccad_app.tcs.protocol import Protocol, parse_protocol

__all__ = ["TCS"]

Module = ModuleTask | PhysicalResource


class TCS:
    """A time-constrained specification: Module-Tasks, physical resources and connections.

    :param name: the Robot-Task's name, for messages.
    :param shared_actuators: allow several producers to feed an actuator port of a physical
        resource (a mission's TCS holds the modules of every Robot-Task it runs; those that
        drive the same robot never run together: the application level checks resource
        conflicts). Module-Task inputs are always fed once.
    """

    def __init__(self, name: str = "tcs", modules: Iterable[Module] = (),
                 shared_actuators: bool = False) -> None:
        self.name = name
        self.shared_actuators = shared_actuators
        self._modules: dict[str, Module] = {}
        self._connections: list[Connection] = []
        self._feeds: dict[str, Connection] = {}
        for module in modules:
            self.add(module)

    # -- building ----------------------------------------------------------------------------

    def add(self, module: Module) -> Module:
        """Add a Module-Task or a physical resource; names are unique."""
        if not isinstance(module, (ModuleTask, PhysicalResource)):
            raise OrccadError(f"TCS '{self.name}': cannot add {module!r}: "
                              f"expected a ModuleTask or a PhysicalResource")
        if module.name in self._modules:
            raise OrccadError(f"TCS '{self.name}': duplicate module name '{module.name}'",
                              getattr(module, "location", None))
        self._modules[module.name] = module
        return module

    def connect(self, producer: str, consumer: str, protocol: str | Protocol = "asyn/asyn",
                location: SourceLocation | None = None) -> Connection:
        """Connect ``producer`` (``"module.port"``, an output) to ``consumer`` (an input)."""
        try:
            connection = Connection(producer, consumer, parse_protocol(protocol), location)
        except OrccadError as error:
            raise OrccadError(error.message, location) from None
        out_port = self._port(connection.producer_module, connection.producer_port, location)
        in_port = self._port(connection.consumer_module, connection.consumer_port, location)
        if out_port.direction is not PortDirection.OUT:
            raise OrccadError(f"'{producer}' is an input port: a connection must start at "
                              f"an output (producer) port", location)
        if in_port.direction is not PortDirection.IN:
            raise OrccadError(f"'{consumer}' is an output port: a connection must end at "
                              f"an input (consumer) port", location)
        if out_port.type != in_port.type or out_port.dim != in_port.dim:
            raise OrccadError(f"type mismatch: '{producer}' is {out_port.type}[{out_port.dim}] "
                              f"but '{consumer}' is {in_port.type}[{in_port.dim}]", location)
        shared = self.shared_actuators and isinstance(self._modules[connection.consumer_module],
                                                      PhysicalResource)
        if consumer in self._feeds and not shared:
            raise OrccadError(f"input port '{consumer}' is fed twice: by "
                              f"'{self._feeds[consumer].producer}' and by '{producer}'", location)
        resource = self._resource_end(connection)
        if resource and connection.protocol is not Protocol.ASYN_ASYN:
            raise OrccadError(f"connection {connection.label}: ports of the physical resource "
                              f"'{resource}' use asyn/asyn (sensors are sampled when read, "
                              f"actuators hold the last write)", location)
        self._feeds.setdefault(consumer, connection)
        self._connections.append(connection)
        return connection

    def _resource_end(self, connection: Connection) -> str | None:
        for name in (connection.producer_module, connection.consumer_module):
            if isinstance(self._modules[name], PhysicalResource):
                return name
        return None

    def _port(self, module: str, port: str, location: SourceLocation | None) -> Port:
        if module not in self._modules:
            known = ", ".join(self._modules) or "none"
            raise OrccadError(f"unknown module '{module}' in port '{module}.{port}' "
                              f"(modules: {known})", location)
        try:
            return self._modules[module].port(port)
        except OrccadError as error:
            raise OrccadError(error.message, location) from None

    # -- queries -----------------------------------------------------------------------------

    @property
    def modules(self) -> dict[str, Module]:
        """All modules by name, in insertion order."""
        return dict(self._modules)

    @property
    def module_tasks(self) -> list[ModuleTask]:
        """The Module-Tasks, in insertion order."""
        return [m for m in self._modules.values() if isinstance(m, ModuleTask)]

    @property
    def resources(self) -> list[PhysicalResource]:
        """The physical resources (plant pseudo modules), in insertion order."""
        return [m for m in self._modules.values() if isinstance(m, PhysicalResource)]

    @property
    def connections(self) -> list[Connection]:
        """The connections, in insertion order."""
        return list(self._connections)

    def module(self, name: str) -> Module:
        """The module called ``name``."""
        try:
            return self._modules[name]
        except KeyError:
            raise OrccadError(f"unknown module '{name}' in TCS '{self.name}'") from None

    def feeding(self, consumer: str) -> Connection | None:
        """The connection feeding input port ``consumer`` (``"module.port"``), if any."""
        return self._feeds.get(consumer)

    def connections_from(self, module: str) -> list[Connection]:
        """Connections whose producer is ``module``, in insertion order."""
        return [c for c in self._connections if c.producer_module == module]

    def connections_to(self, module: str) -> list[Connection]:
        """Connections whose consumer is ``module``, in insertion order."""
        return [c for c in self._connections if c.consumer_module == module]

    def graph(self) -> nx.MultiDiGraph:
        """The TCS graph: a node per module, an edge per connection."""
        graph = nx.MultiDiGraph(name=self.name)
        for name, module in self._modules.items():
            graph.add_node(name, module=module)
        for connection in self._connections:
            graph.add_edge(connection.producer_module, connection.consumer_module,
                           key=connection.consumer, connection=connection)
        return graph

    # -- coherence ---------------------------------------------------------------------------

    def check(self) -> None:
        """Raise :class:`OrccadError` on the first incoherence left after construction:
        a Module-Task input port that nothing feeds, or a TCS without Module-Tasks."""
        if not self.module_tasks:
            raise OrccadError(f"TCS '{self.name}' has no Module-Task")
        for module in self.module_tasks:
            for port in module.inputs:
                ref = f"{module.name}.{port.name}"
                if ref not in self._feeds:
                    raise OrccadError(f"input port '{ref}' is not connected", module.location)
