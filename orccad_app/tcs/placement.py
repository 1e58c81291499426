"""Placement of Module-Tasks on processors: minimize bus traffic under a utilization bound.

Traffic between two Module-Tasks is the message rate their connections would put on the bus
if they ran on different processors [messages/s]: one message per write for push protocols
(:math:`10^9 / T_{producer}`), a request and a reply per read for the pull protocols ``synD`` and
``synDF`` (:math:`2 \\cdot 10^9 / T_{consumer}`). Physical-resource ports are wired to every
processor and cost nothing.

The heuristic (optimal placement is NP-hard, RR-1801 §2.2.3):

1. *clustering*: start from one cluster per Module-Task and repeatedly merge the two clusters
   with the heaviest traffic between them whose joint utilization stays within ``bound``
   (ties by names), until no linked pair can merge;
2. *packing*: clusters by decreasing utilization each go to the processor that already holds
   the most traffic with them, among those where they fit; ties go to the most loaded (best
   fit), then the first processor. A cluster that fits nowhere is placed Module-Task by
   Module-Task the same way;
3. *improvement*: move single Module-Tasks to another processor while a move strictly lowers
   the inter-processor traffic and respects the bound.

It is deterministic. It raises :class:`OrccadError` when a Module-Task fits nowhere, and at
once when the problem exceeds the size budget (:data:`MAX_PROCESSORS` processors,
:data:`MAX_MODULE_TASKS` Module-Tasks: the heuristic is cubic in the Module-Tasks and linear in
the processors per move).
"""

from __future__ import annotations

from dataclasses import dataclass

import networkx as nx

from orccad_app.diagnostics import OrccadError
from orccad_app.tcs.graph import TCS
from orccad_app.tcs.timebase import NS_PER_S

__all__ = ["Placement", "traffic_graph", "suggest_placement", "check_placement_size",
           "MAX_PROCESSORS", "MAX_MODULE_TASKS"]

MAX_PROCESSORS = 256
"""Largest number of processors a placement is computed for (``orccad tcs --processors``
refuses more)."""

MAX_MODULE_TASKS = 500
"""Largest number of Module-Tasks a placement is computed for."""


def check_placement_size(processors: int, module_tasks: int = 0) -> None:
    """Raise :class:`OrccadError` when a placement of ``module_tasks`` on ``processors`` is
    beyond the size budget."""
    if processors > MAX_PROCESSORS:
        raise OrccadError(f"placement on {processors} processors: beyond the budget of "
                          f"{MAX_PROCESSORS} processors (a placement never uses more "
                          f"processors than Module-Tasks)")
    if module_tasks > MAX_MODULE_TASKS:
        raise OrccadError(f"placement of {module_tasks} Module-Tasks: beyond the budget of "
                          f"{MAX_MODULE_TASKS}")


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
    return float(sum(data["traffic"] for u, v, data in graph.edges(data=True)
                     if assignment[u] != assignment[v]))


def _affinity(graph: nx.Graph, node: str, processor: str, assignment: dict[str, str]) -> float:
    return sum(data["traffic"] for other, data in graph[node].items()
               if assignment.get(other) == processor)


def _clusters(graph: nx.Graph, util: dict[str, float], bound: float) -> list[list[str]]:
    clusters = [[name] for name in sorted(util)]
    while True:
        best = None
        for i, first in enumerate(clusters):
            for j in range(i + 1, len(clusters)):
                second = clusters[j]
                load = sum(util[n] for n in first) + sum(util[n] for n in second)
                if load > bound + 1e-12:
                    continue
                weight = sum(graph[u][v]["traffic"] for u in first for v in second
                             if graph.has_edge(u, v))
                if weight > 0 and (best is None or weight > best[0]):
                    best = (weight, i, j)
        if best is None:
            return clusters
        _, i, j = best
        clusters[i] = sorted(clusters[i] + clusters.pop(j))


def _place(members: list[str], graph: nx.Graph, util: dict[str, float], names: list[str],
           loads: dict[str, float], assignment: dict[str, str], bound: float) -> bool:
    need = sum(util[n] for n in members)
    fitting = [p for p in names if loads[p] + need <= bound + 1e-12]
    if not fitting:
        return False
    best = max(fitting, key=lambda p: (sum(_affinity(graph, n, p, assignment) for n in members),
                                       loads[p], -names.index(p)))
    for name in members:
        assignment[name] = best
    loads[best] += need
    return True


def suggest_placement(tcs: TCS, processors: list[str] | int, bound: float = 1.0) -> Placement:
    """Place the TCS's Module-Tasks on ``processors`` (names, or a count ``N`` naming
    ``cpu0 .. cpuN-1``) keeping each processor's utilization <= ``bound``."""
    names = [f"cpu{i}" for i in range(processors)] if isinstance(processors, int) else processors
    if not names:
        raise OrccadError("placement needs at least one processor")
    check_placement_size(len(names), len(tcs.module_tasks))
    graph = traffic_graph(tcs)
    util = {task.name: task.utilization for task in tcs.module_tasks}
    loads = {name: 0.0 for name in names}
    assignment: dict[str, str] = {}
    clusters = _clusters(graph, util, bound)
    clusters.sort(key=lambda c: (-sum(util[n] for n in c), c))
    for cluster in clusters:
        if _place(cluster, graph, util, names, loads, assignment, bound):
            continue
        for task in sorted(cluster, key=lambda n: (-util[n], n)):
            if not _place([task], graph, util, names, loads, assignment, bound):
                raise OrccadError(f"placement: module-task '{task}' (utilization "
                                  f"{util[task]:.3f}) fits on no processor under the bound "
                                  f"{bound}")
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
