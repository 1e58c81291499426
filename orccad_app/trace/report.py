"""The run report: one JSON object (``orccad run --json``) or a text for people.

JSON keys (docs/design.md, *Command line*):

- ``status`` (``done``, ``failed``, ``aborted``, ``recovering``, ``timeout``), ``reason`` (``null`` when done),
  ``mission``, ``seed``, ``sim_time_s``, ``wall_time_s``;
- ``robot_tasks``: per Robot-Task run ``name``, ``args`` (each parameter's actual value at
  that start: run-time arguments evaluated, defaults filled in), ``start_s``, ``end_s``, ``outcome``,
  ``tracking_error`` ``{"rms", "max", "unit"}`` (``rad`` or ``m``, the task function's) (``null`` without a control law);
- ``modules``, keyed ``Task.module``: ``processor``, ``period_s``, ``wcet_s``, ``jobs``
  (completed), ``response_time_max_s``, ``response_time_mean_s``, ``deadline_misses``,
  ``preemptions``, ``blocking_s``; a sporadic one also ``sporadic``: ``min_interarrival_s``,
  ``interrupts``, ``released``, ``deferred``, ``coalesced``, ``min_gap_s``;
- ``timing``, only when ``measured`` (a real-time controller's threads, ``orccad sil
  --realtime``; absent: the executive's timing model): there ``response_time_mean_s``,
  ``preemptions``, ``blocking_s`` and the processors' ``load`` are ``null``, not measured;
- ``processors``, keyed by name: ``load`` (busy fraction, context switches included);
- ``bus``: ``messages``, ``busy_ratio``, ``classes``: per message class (``port_data``: the
  connections' data, request and reply messages; ``event``: observers' signals to an automaton
  on another processor) ``messages``, ``queued_mean_s``, ``queued_max_s`` (the wait for the bus);
- ``reactions``: per automaton processor with a declared reaction time (``automaton@cpu0``),
  ``count`` and ``response_time_max_s`` (from the signal's arrival to the reaction);
- ``exceptions``: ``time_s``, ``name``, ``type`` (1, 2, 3), ``task``; type 1 also ``update``:
  ``module``, ``param``, ``old``, ``new`` and ``ramp`` (``start``, ``end``, ``duration_s``, or
  ``null``);
- ``outputs``: the mission's output signals, in order of emission: an output emitted at most
  three times as one entry per emission, ``time_s``, ``name``, ``value``; one emitted more
  often (a sustained output, a heartbeat) as one entry at its first emission, ``time_s``,
  ``until_s`` (its last), ``name``, ``count`` and ``values`` (``{"min", "max"}`` of its
  numeric values, ``null`` for a pure signal) — as the text report shows them (the trace
  keeps every emission);
- ``injections``: what was raised from outside, in time order: ``time_s``, ``name``,
  ``value``, ``kind`` (``input`` or ``fault``), ``by`` (``--inject`` or ``user``), ``applied``
  (``false`` when the run ended before its time); an input held in the console at every tick
  is one entry with ``until_s`` (its last instant) and ``instants`` (how many);
- ``lateness_s`` (``--realtime`` only): ``median``, ``p99``, ``max``.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any

import numpy as np

from orccad_app.diagnostics import MESSAGE_EXCERPT_COMPONENTS, arguments_text, value_excerpt
from orccad_app.executive.simulation import TimingSource
from orccad_app.mission.result import MissionStatus, RunResult
from orccad_app.trace.recorder import plain_value

__all__ = ["InjectionRecord", "report_dict", "format_report", "lateness_summary"]

#: A signal emitted more often than this is shown as one line ``NAME ×N, first–last s``.
_LISTED_OUTPUTS = 3


@dataclass(frozen=True)
class InjectionRecord:
    """Something raised from outside the mission during a run.

    :param time_ns: when [ns] (simulated time).
    :param name: the input (``Stop``), observer event (``Dive.Leak``) or plant fault
        (``auv.leak``).
    :param value: its value (``None`` for a pure signal).
    :param fault: a plant fault rather than an automaton input.
    :param by: who raised it: ``--inject`` (scheduled) or ``user`` (the console).
    :param until_ns: for an input held at every tick (the console's hold), its last instant
        [ns]; ``time_ns`` is its first.
    :param instants: how many instants it was raised at (a hold: one per tick).
    """

    time_ns: int
    name: str
    value: Any = None
    fault: bool = False
    by: str = "--inject"
    until_ns: int | None = None
    instants: int = 1


def lateness_summary(samples: list[float]) -> dict[str, float]:
    """Median, 99th percentile and maximum lateness [s] (zeros without samples)."""
    if not samples:
        return {"median": 0.0, "p99": 0.0, "max": 0.0}
    values = np.asarray(samples)
    return {"median": float(np.median(values)), "p99": float(np.percentile(values, 99)),
            "max": float(values.max())}


def _modules(result: RunResult) -> dict[str, dict[str, Any]]:
    found = {}
    simulated = result.stats.timing is TimingSource.SIMULATED
    for name, stats in result.stats.tasks.items():
        task = result.modules[name]
        found[name] = {
            "processor": task.processor, "period_s": task.period_ns / 1e9,
            "wcet_s": task.wcet_ns / 1e9, "jobs": stats.completed,
            "response_time_max_s": stats.response_max_ns / 1e9,
            "response_time_mean_s": stats.response_mean_ns / 1e9 if simulated else None,
            "deadline_misses": stats.deadline_misses,
            "preemptions": stats.preemptions if simulated else None,
            "blocking_s": stats.blocking_ns / 1e9 if simulated else None}
        sporadic = result.stats.sporadic.get(name)
        if sporadic is not None:
            found[name]["sporadic"] = {
                "min_interarrival_s": sporadic.min_interarrival_ns / 1e9,
                "interrupts": sporadic.interrupts, "released": sporadic.released,
                "deferred": sporadic.deferred, "coalesced": sporadic.coalesced,
                "min_gap_s": None if sporadic.min_gap_ns < 0 else sporadic.min_gap_ns / 1e9}
    return found


def _bus_classes(result: RunResult) -> dict[str, dict[str, float]]:
    """Per message class (``port_data``, ``event``): messages and queueing delay [s]."""
    bus = result.stats.bus
    if bus is None:
        return {name: {"messages": 0, "queued_mean_s": 0.0, "queued_max_s": 0.0}
                for name in ("port_data", "event")}
    return {name: {"messages": c["messages"], "queued_mean_s": c["queued_mean_ns"] / 1e9,
                   "queued_max_s": c["queued_max_ns"] / 1e9}
            for name, c in bus.by_class().items()}


def _injections(result: RunResult, injections: Iterable[InjectionRecord]) -> list[dict]:
    ordered = sorted(injections, key=lambda i: (i.time_ns, i.name))
    return [{"time_s": i.time_ns / 1e9, "name": i.name, "value": plain_value(i.value),
             "kind": "fault" if i.fault else "input", "by": i.by,
             "applied": i.time_ns <= result.sim_time_ns,
             **({} if i.until_ns is None else {"until_s": i.until_ns / 1e9,
                                                "instants": i.instants})}
            for i in ordered]


def _outputs(result: RunResult) -> list[dict[str, Any]]:
    """The ``outputs`` entries (see the module docstring): the emissions of an output emitted
    more than :data:`_LISTED_OUTPUTS` times grouped into one entry at its first."""
    emitted: dict[str, list[tuple[float, Any]]] = {}
    for t, name, value in result.outputs:
        emitted.setdefault(name, []).append((t / 1e9, plain_value(value)))
    entries: list[dict[str, Any]] = []
    seen: dict[str, int] = {}
    for _, name, _ in result.outputs:
        times = emitted[name]
        index = seen[name] = seen.get(name, -1) + 1
        if len(times) <= _LISTED_OUTPUTS:
            time_s, value = times[index]
            entries.append({"time_s": time_s, "name": name, "value": value})
        elif index == 0:
            numbers = [v for _, v in times if isinstance(v, (int, float))]
            entries.append({"time_s": times[0][0], "until_s": times[-1][0], "name": name,
                            "count": len(times),
                            "values": {"min": min(numbers), "max": max(numbers)}
                            if numbers else None})
    return entries


def report_dict(result: RunResult,
                injections: Iterable[InjectionRecord] = ()) -> dict[str, Any]:
    """The JSON report of ``result`` and what was ``injections`` (see the module docstring)."""
    bus = result.stats.bus
    report: dict[str, Any] = {
        "mission": result.mission, "status": result.status, "reason": result.reason,
        "seed": result.seed, "sim_time_s": result.sim_time_ns / 1e9,
        "wall_time_s": result.wall_time_s,
        "robot_tasks": [record.as_dict() for record in result.robot_tasks],
        "modules": _modules(result),
        "processors": {name: {"load": stats.load
                              if result.stats.timing is TimingSource.SIMULATED else None}
                       for name, stats in result.stats.processors.items()},
        "bus": {"messages": bus.messages if bus else 0,
                "busy_ratio": bus.busy_ratio if bus else 0.0,
                "classes": _bus_classes(result)},
        "reactions": {name: {"count": stats.completed,
                             "response_time_max_s": stats.response_max_ns / 1e9}
                      for name, stats in result.stats.reactions.items() if stats.released},
        "exceptions": [record.as_dict() for record in result.exceptions],
        "outputs": _outputs(result),
        "injections": _injections(result, injections),
    }
    if result.stats.timing is TimingSource.MEASURED:
        report["timing"] = TimingSource.MEASURED.value
    if result.lateness_s is not None:
        report["lateness_s"] = lateness_summary(result.lateness_s)
    return report


def _ms(seconds: float) -> str:
    return f"{seconds * 1e3:.3f}"


def _task_label(task: dict[str, Any]) -> str:
    """``GoTo(target=[10, 0, 15])``: the task with its actual arguments."""
    args = task.get("args") or {}
    return task["name"] + (f"({arguments_text(args)})" if args else "")


def _task_lines(report: dict[str, Any]) -> list[str]:
    lines = ["Robot-Tasks:"]
    width = max([16, *(len(_task_label(t)) for t in report["robot_tasks"] or [])])
    for task in report["robot_tasks"] or []:
        end = "…" if task["end_s"] is None else f"{task['end_s']:.3f}"
        error = task["tracking_error"]
        figures = ("" if error is None else
                   f"   tracking error RMS {error['rms']:.3e} {error['unit']}, "
                   f"max {error['max']:.3e} {error['unit']}")
        lines.append(f"  {_task_label(task):<{width}} {task['start_s']:.3f} → {end} s  "
                     f"{task['outcome']}{figures}")
    if not report["robot_tasks"]:
        lines.append("  (none started)")
    return lines


def _module_lines(report: dict[str, Any]) -> list[str]:
    lines = [f"  {'module':<28} {'cpu':<6} {'T ms':>6} {'C ms':>6} {'jobs':>6} "
             f"{'R max ms':>9} {'R mean ms':>9} {'misses':>6} {'preempt':>7}"]
    for name, m in report["modules"].items():
        if not m["jobs"]:
            continue
        mean, preempted = m["response_time_mean_s"], m["preemptions"]
        lines.append(f"  {name:<28} {m['processor']:<6} {_ms(m['period_s']):>6} "
                     f"{_ms(m['wcet_s']):>6} {m['jobs']:>6} {_ms(m['response_time_max_s']):>9} "
                     f"{'—' if mean is None else _ms(mean):>9} {m['deadline_misses']:>6} "
                     f"{'—' if preempted is None else preempted:>7}")
    for name, m in report["modules"].items():
        sporadic = m.get("sporadic")
        if sporadic:
            lines.append(f"  {name}: sporadic, min inter-arrival {_ms(sporadic['min_interarrival_s'])}"
                         f" ms: {sporadic['interrupts']} interrupts, {sporadic['released']} "
                         f"releases, {sporadic['deferred']} deferred, {sporadic['coalesced']} "
                         f"coalesced")
    return lines


def _value_text(value: Any) -> str:
    """``(VALUE)`` for a line of the text report: a long vector is cut (the JSON report keeps
    it whole)."""
    if value is None:
        return ""
    if isinstance(value, float):
        return f"({value:g})"
    if isinstance(value, (list, tuple)) and len(value) > MESSAGE_EXCERPT_COMPONENTS:
        return f"({value_excerpt(value)})"
    return f"({value})"


def _output_lines(report: dict[str, Any]) -> list[str]:
    """One line per output signal, in order of first emission: each emission when there are
    few (``Retry(1) 3.105 s``), else ``Beat ×3992, 1.500–4.700 s`` (a sustained output)."""
    groups: dict[str, list[dict]] = {}
    for output in report["outputs"]:
        groups.setdefault(output["name"], []).append(output)
    lines = ["Outputs:"]
    for name, emitted in groups.items():
        if "count" not in emitted[0]:
            shown = ", ".join(f"{name}{_value_text(o['value'])} {o['time_s']:.3f} s"
                              for o in emitted)
            lines.append(f"  {shown}")
            continue
        group = emitted[0]
        values = group["values"]
        span = f", values {values['min']:g}–{values['max']:g}" if values else ""
        lines.append(f"  {name} ×{group['count']}, {group['time_s']:.3f}–"
                     f"{group['until_s']:.3f} s{span}")
    return lines


def _injection_lines(report: dict[str, Any]) -> list[str]:
    lines = ["Injections:"]
    for i in report["injections"]:
        what = (f"{i['name']} = {i['value']} (plant fault" if i["kind"] == "fault" else
                f"{i['name']}{_value_text(i['value'])} (input")
        late = "" if i["applied"] else ", after the end: not applied"
        if "until_s" in i:  # held: one line for all its instants
            lines.append(f"  {i['time_s']:.3f}–{i['until_s']:.3f} s  {what}, {i['by']}, at "
                         f"{i['instants']} instants{late})")
            continue
        lines.append(f"  {i['time_s']:.3f} s  {what}, {i['by']}{late})")
    return lines


def _exception_lines(result: RunResult) -> list[str]:
    """One line per exception; consecutive ones that read the same (a type-1 update repeated
    at its bound: ``kp 800 -> 800``) as one line ``first–last s … ×N``."""
    groups: list[tuple[float, float, str, int]] = []
    for record in result.exceptions:
        change = f": {record.update.text()}" if record.update is not None else ""
        text = (f"{record.name} (type {record.type.number}"
                f"{', ' + record.task if record.task else ''}){change}")
        time_s = record.time_ns / 1e9
        if groups and groups[-1][2] == text:
            first, _, _, count = groups[-1]
            groups[-1] = (first, time_s, text, count + 1)
        else:
            groups.append((time_s, time_s, text, 1))
    lines = ["Exceptions:"]
    for first, last, text, count in groups:
        when = f"{first:.3f} s" if count == 1 else f"{first:.3f}–{last:.3f} s"
        lines.append(f"  {when}  {text}" + (f" ×{count}" if count > 1 else ""))
    return lines


def format_report(result: RunResult, injections: Iterable[InjectionRecord] = ()) -> str:
    """The human report: the story first (status, Robot-Tasks, exceptions, injections,
    outputs), then the Module-Tasks' timing, processors and bus."""
    report = report_dict(result, injections)
    ratio = report["sim_time_s"] / report["wall_time_s"] if report["wall_time_s"] else 0.0
    status = report["status"] + (f" ({report['reason']})" if report["reason"] else "")
    lines = [f"mission {report['mission']}: {status}"]
    if report["status"] == MissionStatus.RECOVERING:
        lines.append(f"  aborted by {report['reason']}; its 'on fatal' recovery was still "
                     f"running at {report['sim_time_s']:g} s (the run's horizon)")
    lines += [f"  simulated {report['sim_time_s']:.3f} s in {report['wall_time_s']:.2f} s wall "
             f"({ratio:.1f}× real time), seed {report['seed']}"]
    lines += _task_lines(report)
    if report["exceptions"]:
        lines += _exception_lines(result)
    if report["injections"]:
        lines += _injection_lines(report)
    if report["outputs"]:
        lines += _output_lines(report)
    lines.append("Module-Tasks (times in ms):")
    lines += _module_lines(report)
    if report.get("timing") != TimingSource.MEASURED.value:
        loads = ", ".join(f"{name} {p['load']:.1%}" for name, p in report["processors"].items())
        lines.append(f"Processors: load {loads}")
    else:
        lines.append("Processors: load not measured on the controller's threads (— above: "
                     "not measured)")
    bus = report["bus"]
    lines.append(f"Bus: {bus['messages']} messages, busy {bus['busy_ratio']:.1%}")
    for name, label in (("port_data", "port data"), ("event", "event signals")):
        c = bus["classes"][name]
        if c["messages"]:
            lines.append(f"  {label}: {c['messages']} messages, queueing mean "
                         f"{_ms(c['queued_mean_s'])} ms, max {_ms(c['queued_max_s'])} ms")
    for name, r in report["reactions"].items():
        lines.append(f"Reactions on {name.removeprefix('automaton@')}: {r['count']}, "
                     f"longest {_ms(r['response_time_max_s'])} ms (signal delivered to "
                     f"reaction done)")
    if "lateness_s" in report:
        late = report["lateness_s"]
        lines.append(f"Lateness behind the wall clock: median {_ms(late['median'])} ms, "
                     f"p99 {_ms(late['p99'])} ms, max {_ms(late['max'])} ms")
    return "\n".join(lines)
