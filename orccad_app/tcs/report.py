"""Everything ``orccad tcs`` says about a TCS: graph, coherence, schedulability, deadlock,
placement — as one :class:`TcsReport`, printed as text, Graphviz DOT or JSON.

- **graph**: Module-Tasks (kind, processor, priority, period ``T``, execution time ``C``,
  utilization) and connections with their protocols;
- **coherence**: :meth:`~orccad_app.tcs.graph.TCS.check` (every input fed, resources wired
  ``asyn/asyn``; the rest is checked while the TCS is built);
- **schedulability**: per-processor utilization and the analysis of the executive's run
  (:func:`~orccad_app.tcs.schedulability.analyse_timing`): fixed priority or EDF, context
  switches, the protocols' blocking (or a named "unschedulable by construction") and the bus's
  delay per message class; with no blocking and all tasks released together the fixed-priority
  figures are exactly the worst responses the executive measures;
- **deadlock**: cycles of blocking protocol ends
  (:func:`~orccad_app.tcs.deadlock.find_deadlock_cycles`);
- **placement**: a placement on ``N`` processors minimizing bus traffic under a utilization
  bound (:func:`~orccad_app.tcs.placement.suggest_placement`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from orccad_app.diagnostics import OrccadError
from orccad_app.tcs.analysis import utilization
from orccad_app.tcs.phasing import Activation
from orccad_app.tcs.bus_delay import BusModel
from orccad_app.tcs.deadlock import DeadlockCycle, find_deadlock_cycles
from orccad_app.tcs.graph import TCS
from orccad_app.tcs.module_task import ModuleTask, PhysicalResource
from orccad_app.tcs.placement import Placement, suggest_placement, traffic_graph
from orccad_app.tcs.schedulability import Schedulability, TaskTiming, analyse_timing

__all__ = ["TcsReport", "analyse", "to_dot", "to_text", "to_dict"]


@dataclass
class TcsReport:
    """The analyses of one TCS.

    :param tcs: the TCS.
    :param coherence: ``None`` when coherent, else the first incoherence's message.
    :param loads: processor -> utilization.
    :param timing: the schedulability analysis.
    :param cycles: potential deadlock cycles.
    :param placement: the suggested placement, ``None`` when none fits (see ``placement_error``).
    :param placement_error: why no placement fits.
    :param bound: the utilization bound of the placement.
    """

    tcs: TCS
    coherence: str | None
    loads: dict[str, float]
    timing: Schedulability
    cycles: list[DeadlockCycle]
    placement: Placement | None
    placement_error: str | None
    bound: float

    @property
    def ok(self) -> bool:
        """Coherent, schedulable and free of potential deadlocks."""
        return self.coherence is None and not self.cycles and self.timing.ok


def analyse(tcs: TCS, processors: int | list[str] = 2, bound: float = 1.0,
            context_switch_ns: int = 0, scheduler: str = "fp", bus: BusModel | None = None,
            groups: dict[str, int | None] | None = None) -> TcsReport:
    """Run every analysis of ``tcs``; placement on ``processors`` under ``bound``; timing
    under ``scheduler`` with ``context_switch_ns`` and ``bus``, Module-Tasks activated in
    ``groups`` (see :func:`~orccad_app.tcs.schedulability.analyse_timing`)."""
    try:
        tcs.check()
        coherence = None
    except OrccadError as error:
        coherence = error.message
    tasks = tcs.module_tasks
    try:
        placement, placement_error = suggest_placement(tcs, processors, bound), None
    except OrccadError as error:
        placement, placement_error = None, error.message
    timing = analyse_timing(tcs, scheduler, context_switch_ns, bus, groups)
    return TcsReport(tcs, coherence, utilization(tasks), timing, find_deadlock_cycles(tcs),
                     placement, placement_error, bound)


def _ms(ns: int | None) -> str:
    return "—" if ns is None else f"{ns / 1e6:g}"


def _module_lines(report: TcsReport) -> list[str]:
    lines = [f"  {'module':<20} {'kind':<18} {'cpu':<6} {'prio':>4} {'T ms':>7} {'C ms':>7} "
             f"{'U':>6}"]
    for task in report.tcs.module_tasks:
        lines.append(f"  {task.name:<20} {task.kind or '-':<18} {task.processor:<6} "
                     f"{task.priority:>4} {_ms(task.period_ns):>7} {_ms(task.wcet_ns):>7} "
                     f"{task.utilization:>6.3f}"
                     + ("  sporadic: T = min inter-arrival"
                        if task.activation is Activation.SPORADIC else ""))
    for resource in report.tcs.resources:
        ports = ", ".join(f"{p.name} ({'sensor' if p.direction.value == 'out' else 'actuator'})"
                          for p in resource.ports)
        lines.append(f"  {resource.name:<20} physical resource: {ports}")
    return lines


def _verdict(result: TaskTiming) -> str:
    if result.schedulable:
        return "ok"
    return "MAY MISS its deadline: " + (result.problem or "")


def _schedule_lines(report: TcsReport) -> list[str]:
    lines = []
    timing = report.timing
    for processor, load in report.loads.items():
        lines.append(f"  {processor}: utilization {load:.3f}")
        for task in sorted((t for t in report.tcs.module_tasks if t.processor == processor),
                           key=lambda t: (t.priority, t.name)):
            result = timing.tasks[task.name]
            blocking = ""
            if result.schedulable and (result.read_wait_ns or result.write_wait_ns):
                blocking = (f"  (read wait {_ms(result.read_wait_ns)} ms, write wait "
                            f"{_ms(result.write_wait_ns)} ms)")
            lines.append(f"    {task.name:<20} prio {task.priority:>2}  R = "
                         f"{_ms(result.response_ns):>6} ms  D = {_ms(result.deadline_ns):>6} ms"
                         f"  {_verdict(result)}{blocking}")
    lines += _bus_lines(timing)
    lines += [f"  note: {note}" for note in timing.notes]
    return lines


def _bus_lines(timing: Schedulability) -> list[str]:
    if not any(m.transfer_ns for m in timing.messages):
        return []  # no transfer time given (--bus-us): messages cost nothing
    load = timing.messages[0].bus_utilization
    lines = [f"  bus: utilization {load:.3f}, worst delay {_ms(timing.bus_busy_ns)} ms "
             f"(FIFO); per message class:"]
    for m in timing.messages:
        lines.append(f"    {m.connection} {m.kind}: {m.rate_hz:g}/s, transfer "
                     f"{_ms(m.transfer_ns)} ms, queueing <= {_ms(m.queueing_ns)} ms")
    return lines


def _placement_lines(report: TcsReport) -> list[str]:
    if report.placement is None:
        return [f"  none: {report.placement_error}"]
    placement = report.placement
    names = sorted(set(placement.loads))
    lines = [f"  {p}: {', '.join(m for m, q in placement.assignment.items() if q == p) or '—'}"
             f"  (utilization {placement.loads[p]:.3f})" for p in names]
    lines.append(f"  inter-processor traffic: {placement.bus_traffic_hz:g} messages/s")
    return lines


def to_text(report: TcsReport) -> str:
    """The human-readable report."""
    tcs = report.tcs
    lines = [f"TCS of {tcs.name}", "Module-Tasks:", *_module_lines(report), "Connections:"]
    lines += [f"  {c.label}" for c in tcs.connections]
    lines.append("Coherence: " + ("ok" if report.coherence is None else report.coherence))
    scheduler = ("EDF" if report.timing.scheduler == "edf"
                 else "fixed priority")
    lines.append(f"Schedulability ({scheduler}, preemptive; protocol blocking, context switches "
                 f"and bus included):")
    lines += _schedule_lines(report)
    if report.cycles:
        lines.append("Deadlock analysis: potential deadlock cycles of blocking protocols:")
        lines += [f"  {cycle.describe()}" for cycle in report.cycles]
    else:
        lines.append("Deadlock analysis: no cycle of blocking protocols")
    count = len(report.placement.loads) if report.placement else "?"
    lines.append(f"Suggested placement on {count} processors (utilization bound "
                 f"{report.bound:g}, minimizing bus traffic):")
    lines += _placement_lines(report)
    return "\n".join(lines)


def _quote(text: str) -> str:
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'


def to_dot(tcs: TCS) -> str:
    """The TCS graph in Graphviz DOT: Module-Tasks as boxes (clustered by processor),
    physical resources as double octagons, one edge per connection labelled with its ports
    and protocol."""
    lines = [f"digraph {_quote(tcs.name)} {{", "  rankdir=LR;", "  node [shape=box];"]
    by_processor: dict[str, list[ModuleTask]] = {}
    for task in tcs.module_tasks:
        by_processor.setdefault(task.processor, []).append(task)
    for index, (processor, tasks) in enumerate(by_processor.items()):
        lines.append(f"  subgraph cluster_{index} {{ label={_quote(processor)};")
        for task in tasks:
            label = f"{task.name}\\nT={_ms(task.period_ns)} ms C={_ms(task.wcet_ns)} ms " \
                    f"p{task.priority}"
            lines.append(f"    {_quote(task.name)} [label=\"{label}\"];")
        lines.append("  }")
    for resource in tcs.resources:
        lines.append(f"  {_quote(resource.name)} [shape=doubleoctagon];")
    for c in tcs.connections:
        label = f"{c.producer_port}→{c.consumer_port}\\n{c.protocol.value}"
        style = "" if c.protocol.value == "asyn/asyn" else ", style=bold"
        lines.append(f"  {_quote(c.producer_module)} -> {_quote(c.consumer_module)} "
                     f"[label=\"{label}\"{style}];")
    lines.append("}")
    return "\n".join(lines)


def _seconds(ns: int | None) -> float | None:
    return None if ns is None else ns / 1e9


def _module_dict(task: ModuleTask | PhysicalResource, report: TcsReport) -> dict[str, Any]:
    if isinstance(task, PhysicalResource):
        return {"resource": True, "ports": [p.name for p in task.ports]}
    result = report.timing.tasks[task.name]
    return {"kind": task.kind, "processor": task.processor, "priority": task.priority,
            "activation": task.activation.value,
            "period_s": task.period_ns / 1e9, "wcet_s": task.wcet_ns / 1e9,
            "deadline_s": task.deadline_ns / 1e9, "utilization": task.utilization,
            "read_wait_s": _seconds(result.read_wait_ns),
            "write_wait_s": _seconds(result.write_wait_ns),
            "response_time_s": _seconds(result.response_ns),
            "schedulable": result.schedulable, "problem": result.problem}


def to_dict(report: TcsReport) -> dict[str, Any]:
    """The JSON form: modules, connections, loads, bus, deadlock cycles, placement (strict
    JSON: every number is finite)."""
    placement = report.placement
    traffic = traffic_graph(report.tcs)
    timing = report.timing
    return {
        "task": report.tcs.name,
        "ok": report.ok,
        "coherence": report.coherence,
        "scheduler": timing.scheduler,
        "modules": {name: _module_dict(m, report) for name, m in report.tcs.modules.items()},
        "connections": [{"producer": c.producer, "consumer": c.consumer,
                         "protocol": c.protocol.value} for c in report.tcs.connections],
        "processors": {name: {"utilization": load} for name, load in report.loads.items()},
        "bus": {"worst_delay_s": _seconds(timing.bus_busy_ns),
                "messages": [{"connection": m.connection, "kind": m.kind,
                              "rate_hz": m.rate_hz, "transfer_s": m.transfer_ns / 1e9,
                              "queueing_s": _seconds(m.queueing_ns)}
                             for m in timing.messages]},
        "notes": list(timing.notes),
        "deadlock_cycles": [list(cycle.ports) for cycle in report.cycles],
        "placement": None if placement is None else {
            "assignment": placement.assignment, "loads": placement.loads,
            "bus_traffic_hz": placement.bus_traffic_hz},
        "traffic_hz": {f"{u}--{v}": d["traffic"] for u, v, d in traffic.edges(data=True)},
    }

