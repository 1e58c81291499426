"""Placement of Module-Tasks on processors: minimize bus traffic under a utilization bound.

Traffic between two Module-Tasks is the message rate their connections would put on the bus
if they ran on different processors [messages/s]: one message per write for push protocols
(:math:`10^9 / T_{producer}`), a request and a reply per read for the pull protocols ``synD`` and
``synDF`` (:math:`2 \\cdot 10^9 / T_{consumer}`). Physical-resource ports are wired to every
processor and cost nothing.

The heuristic (optimal placement is NP-hard, RR-1801 §2.2.3):

1. *greedy*: Module-Tasks by decreasing utilization (ties by name) each go to the processor
   that already holds the most traffic with them, among processors whose utilization stays
   within ``bound``; ties go to the least loaded, then the first processor;
2. *improvement*: move single Module-Tasks to another processor while a move strictly lowers
   the inter-processor traffic and respects the bound (first improving move in a fixed order,
   repeated until none is left).

It is deterministic. It raises :class:`OrccadError` when a Module-Task fits nowhere.
"""

from __future__ import annotations

from dataclasses import dataclass

import networkx as nx

from orccad_app.diagnostics import OrccadError
from orccad_app.tcs.graph import TCS
from orccad_app.tcs.timebase import NS_PER_S

__all__ = ["Placement", "traffic_graph", "suggest_placement"]


@dataclass(frozen=True, slots=True)
class Placement:
    """A suggested placement.

    :param assignment: Module-Task name -> processor name.
    :param loads: processor name -> utilization.
    :param bus_traffic_hz: inter-processor traffic of this placement [messages/s].
    """

    assignment: dict[str, str]
    loads: dict[str, float]
    bus_traffic_hz: float


def traffic_graph(tcs: TCS) -> nx.Graph:
    """Undirected graph of Module-Tasks, edge weight ``traffic`` in [messages/s]."""
    graph = nx.Graph()
    tasks = {task.name: task for task in tcs.module_tasks}
    graph.add_nodes_from(tasks)
    for connection in tcs.connections:
        producer = tasks.get(connection.producer_module)
        consumer = tasks.get(connection.consumer_module)
        if producer is None or consumer is None or producer is consumer:
            continue
        if connection.protocol.is_pull:
            rate = 2 * NS_PER_S / consumer.period_ns
        else:
            rate = NS_PER_S / producer.period_ns
        previous = graph.get_edge_data(producer.name, consumer.name, {"traffic": 0.0})
        graph.add_edge(producer.name, consumer.name, traffic=previous["traffic"] + rate)
    return graph


def _cut(graph: nx.Graph, assignment: dict[str, str]) -> float:
    return sum(data["traffic"] for u, v, data in graph.edges(data=True)
               if assignment[u] != assignment[v])


def _affinity(graph: nx.Graph, node: str, processor: str, assignment: dict[str, str]) -> float:
    return sum(data["traffic"] for other, data in graph[node].items()
               if assignment.get(other) == processor)


def suggest_placement(tcs: TCS, processors: list[str] | int, bound: float = 1.0) -> Placement:
    """Place the TCS's Module-Tasks on ``processors`` (names, or a count ``N`` naming
    ``cpu0 .. cpuN-1``) keeping each processor's utilization <= ``bound``."""
    names = [f"cpu{i}" for i in range(processors)] if isinstance(processors, int) else processors
    if not names:
        raise OrccadError("placement needs at least one processor")
    graph = traffic_graph(tcs)
    util = {task.name: task.utilization for task in tcs.module_tasks}
    loads = {name: 0.0 for name in names}
    assignment: dict[str, str] = {}
    for task in sorted(util, key=lambda n: (-util[n], n)):
        fitting = [p for p in names if loads[p] + util[task] <= bound + 1e-12]
        if not fitting:
            raise OrccadError(f"placement: module-task '{task}' (utilization {util[task]:.3f}) "
                              f"fits on no processor under the bound {bound}")
        best = max(fitting, key=lambda p: (_affinity(graph, task, p, assignment), -loads[p],
                                           -names.index(p)))
        assignment[task] = best
        loads[best] += util[task]
    _improve(graph, util, names, loads, assignment, bound)
    ordered = {task.name: assignment[task.name] for task in tcs.module_tasks}
    return Placement(ordered, loads, _cut(graph, assignment))


def _improve(graph: nx.Graph, util: dict[str, float], names: list[str],
             loads: dict[str, float], assignment: dict[str, str], bound: float) -> None:
    improved = True
    while improved:
        improved = False
        for task in sorted(assignment):
            here = assignment[task]
            stay = _affinity(graph, task, here, assignment)
            for target in names:
                if target == here or loads[target] + util[task] > bound + 1e-12:
                    continue
                if _affinity(graph, task, target, assignment) > stay + 1e-9:
                    assignment[task] = target
                    loads[here] -= util[task]
                    loads[target] += util[task]
                    improved = True
                    break
