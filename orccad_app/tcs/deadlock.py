"""Static deadlock analysis of a TCS: cycles of blocking protocol ends (docs/design.md, *Deadlock*).

Each job of a Module-Task performs its port operations in a fixed cyclic order: read every input
(declaration order), then write every output (declaration order, one write per connection). An
operation *blocks* when its protocol end may wait for the other module: reads of ``syn``,
``synF`` and ``synDF`` consumer ends, writes of ``syn`` and ``synF`` producer ends (``synD``
reads only wait for the bus, which always answers).

The analysis builds a wait-for graph over blocking operations: an operation ``u`` of module ``M``
waiting for its partner operation ``v`` of module ``N`` depends on every *other* blocking
operation of ``N`` (the job cycle is cyclic: ``N`` may be stuck at any of them before it reaches
``v`` again). A cycle in that graph is a **potential deadlock**, reported with the ports involved
(``module.port``). The analysis is conservative: it may flag a cycle that particular timings never
reach, never the reverse; the executive detects actual deadlocks at run time.
"""

from __future__ import annotations

from dataclasses import dataclass

import networkx as nx

from orccad_app.diagnostics import OrccadError
from orccad_app.tcs.connection import Connection
from orccad_app.tcs.graph import TCS

__all__ = ["DeadlockCycle", "find_deadlock_cycles", "check_deadlock_free"]


@dataclass(frozen=True, slots=True)
class DeadlockCycle:
    """A cycle of blocking operations, each waiting for the next.

    :param steps: ``(port, operation, protocol)`` per step, ``port`` as ``module.port`` and
        ``operation`` ``read`` or ``write``.
    """

    steps: tuple[tuple[str, str, str], ...]

    @property
    def modules(self) -> tuple[str, ...]:
        """The modules on the cycle, in cycle order."""
        return tuple(port.rpartition(".")[0] for port, _, _ in self.steps)

    @property
    def ports(self) -> tuple[str, ...]:
        """The blocking ports on the cycle, ``module.port``."""
        return tuple(port for port, _, _ in self.steps)

    def describe(self) -> str:
        """``a.x (read, asyn/syn) -> b.y (write, syn/asyn) -> a.x``."""
        parts = [f"{port} ({op}, {protocol})" for port, op, protocol in self.steps]
        return " -> ".join(parts + [self.steps[0][0]])


_Op = tuple[str, str, Connection]  # (module, "read"|"write", connection)


def _operations(tcs: TCS) -> dict[str, list[_Op]]:
    """Each Module-Task's port operations in job order."""
    ops: dict[str, list[_Op]] = {}
    for task in tcs.module_tasks:
        sequence: list[_Op] = []
        for port in task.inputs:
            connection = tcs.feeding(f"{task.name}.{port.name}")
            if connection is not None:
                sequence.append((task.name, "read", connection))
        outgoing = tcs.connections_from(task.name)
        for port in task.outputs:
            for connection in outgoing:
                if connection.producer_port == port.name:
                    sequence.append((task.name, "write", connection))
        ops[task.name] = sequence
    return ops


def _blocks(op: _Op) -> bool:
    _, kind, connection = op
    protocol = connection.protocol
    if kind == "read":
        return protocol.consumer_waits_for_producer
    return protocol.producer_may_block


def _partner(op: _Op) -> _Op:
    _, kind, connection = op
    if kind == "read":
        return (connection.producer_module, "write", connection)
    return (connection.consumer_module, "read", connection)


def _wait_graph(tcs: TCS) -> nx.DiGraph:
    ops = _operations(tcs)
    graph = nx.DiGraph()
    for sequence in ops.values():
        for op in sequence:
            if not _blocks(op):
                continue
            graph.add_node(op)
            partner = _partner(op)
            for other in ops.get(partner[0], ()):
                if other != partner and _blocks(other):
                    graph.add_edge(op, other)
    return graph


def _step(op: _Op) -> tuple[str, str, str]:
    _, kind, connection = op
    port = connection.consumer if kind == "read" else connection.producer
    return (port, kind, connection.protocol.value)


def find_deadlock_cycles(tcs: TCS) -> list[DeadlockCycle]:
    """One cycle per strongly connected group of blocking operations, in a stable order."""
    graph = _wait_graph(tcs)
    order = {op: index for index, op in enumerate(graph.nodes)}
    cycles = []
    for component in nx.strongly_connected_components(graph):
        start = min(component, key=order.__getitem__)
        if len(component) == 1 and not graph.has_edge(start, start):
            continue
        edges = nx.find_cycle(graph.subgraph(component), source=start)
        cycles.append((order[start], DeadlockCycle(tuple(_step(u) for u, _ in edges))))
    return [cycle for _, cycle in sorted(cycles, key=lambda item: item[0])]


def check_deadlock_free(tcs: TCS) -> None:
    """Raise :class:`OrccadError` naming the ports of the first potential deadlock cycle."""
    cycles = find_deadlock_cycles(tcs)
    if cycles:
        raise OrccadError(f"potential deadlock in TCS '{tcs.name}': {cycles[0].describe()}")
