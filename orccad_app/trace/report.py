"""The run report: one JSON object (``orccad run --json``) or a text for people.

JSON keys (docs/design.md, *Command line*):

- ``status`` (``done``, ``failed``, ``aborted``, ``timeout``), ``reason`` (``null`` when done),
  ``mission``, ``seed``, ``sim_time_s``, ``wall_time_s``;
- ``robot_tasks``: per Robot-Task run ``name``, ``start_s``, ``end_s``, ``outcome``,
  ``tracking_error`` ``{"rms", "max"}`` [rad] (``null`` without a control law);
- ``modules``, keyed ``Task.module``: ``processor``, ``period_s``, ``wcet_s``, ``jobs``
  (completed), ``response_time_max_s``, ``response_time_mean_s``, ``deadline_misses``,
  ``preemptions``, ``blocking_s``;
- ``processors``, keyed by name: ``load`` (busy fraction, context switches included);
- ``bus``: ``messages``, ``busy_ratio``;
- ``exceptions``: ``time_s``, ``name``, ``type`` (1, 2, 3), ``task``;
- ``outputs``: the mission's output signals, ``time_s``, ``name``, ``value``;
- ``lateness_s`` (``--realtime`` only): ``median``, ``p99``, ``max``.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from orccad_app.mission.result import RunResult
from orccad_app.trace.recorder import plain_value

__all__ = ["report_dict", "format_report", "lateness_summary"]


def lateness_summary(samples: list[float]) -> dict[str, float]:
    """Median, 99th percentile and maximum lateness [s] (zeros without samples)."""
    if not samples:
        return {"median": 0.0, "p99": 0.0, "max": 0.0}
    values = np.asarray(samples)
    return {"median": float(np.median(values)), "p99": float(np.percentile(values, 99)),
            "max": float(values.max())}


def _modules(result: RunResult) -> dict[str, dict[str, Any]]:
    found = {}
    for name, stats in result.stats.tasks.items():
        task = result.modules[name]
        found[name] = {
            "processor": task.processor, "period_s": task.period_ns / 1e9,
            "wcet_s": task.wcet_ns / 1e9, "jobs": stats.completed,
            "response_time_max_s": stats.response_max_ns / 1e9,
            "response_time_mean_s": stats.response_mean_ns / 1e9,
            "deadline_misses": stats.deadline_misses, "preemptions": stats.preemptions,
            "blocking_s": stats.blocking_ns / 1e9}
    return found


def report_dict(result: RunResult) -> dict[str, Any]:
    """The JSON report of ``result`` (see the module docstring)."""
    bus = result.stats.bus
    report = {
        "mission": result.mission, "status": result.status, "reason": result.reason,
        "seed": result.seed, "sim_time_s": result.sim_time_ns / 1e9,
        "wall_time_s": result.wall_time_s,
        "robot_tasks": [record.as_dict() for record in result.robot_tasks],
        "modules": _modules(result),
        "processors": {name: {"load": stats.load}
                       for name, stats in result.stats.processors.items()},
        "bus": {"messages": bus.messages if bus else 0,
                "busy_ratio": bus.busy_ratio if bus else 0.0},
        "exceptions": [record.as_dict() for record in result.exceptions],
        "outputs": [{"time_s": t / 1e9, "name": name, "value": plain_value(value)}
                    for t, name, value in result.outputs],
    }
    if result.lateness_s is not None:
        report["lateness_s"] = lateness_summary(result.lateness_s)
    return report


def _ms(seconds: float) -> str:
    return f"{seconds * 1e3:.3f}"


def _task_lines(report: dict[str, Any]) -> list[str]:
    lines = ["Robot-Tasks:"]
    for task in report["robot_tasks"] or []:
        end = "…" if task["end_s"] is None else f"{task['end_s']:.3f}"
        error = task["tracking_error"]
        figures = ("" if error is None else
                   f"   tracking error RMS {error['rms']:.3e} rad, max {error['max']:.3e} rad")
        lines.append(f"  {task['name']:<16} {task['start_s']:.3f} → {end} s  "
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
        lines.append(f"  {name:<28} {m['processor']:<6} {_ms(m['period_s']):>6} "
                     f"{_ms(m['wcet_s']):>6} {m['jobs']:>6} {_ms(m['response_time_max_s']):>9} "
                     f"{_ms(m['response_time_mean_s']):>9} {m['deadline_misses']:>6} "
                     f"{m['preemptions']:>7}")
    return lines


def format_report(result: RunResult) -> str:
    """The human report: status, Robot-Tasks, exceptions, modules, processors, bus."""
    report = report_dict(result)
    ratio = report["sim_time_s"] / report["wall_time_s"] if report["wall_time_s"] else 0.0
    status = report["status"] + (f" ({report['reason']})" if report["reason"] else "")
    lines = [f"mission {report['mission']}: {status}",
             f"  simulated {report['sim_time_s']:.3f} s in {report['wall_time_s']:.2f} s wall "
             f"({ratio:.1f}× real time), seed {report['seed']}"]
    lines += _task_lines(report)
    if report["exceptions"]:
        lines.append("Exceptions:")
        for e in report["exceptions"]:
            lines.append(f"  {e['time_s']:.3f} s  {e['name']} (type {e['type']}"
                         f"{', ' + e['task'] if e['task'] else ''})")
    if report["outputs"]:
        shown = ", ".join(f"{o['name']}@{o['time_s']:g}" for o in report["outputs"][:12])
        more = len(report["outputs"]) - 12
        lines.append(f"Outputs: {shown}{f' … (+{more})' if more > 0 else ''}")
    lines.append("Module-Tasks (times in ms):")
    lines += _module_lines(report)
    loads = ", ".join(f"{name} {p['load']:.1%}" for name, p in report["processors"].items())
    lines.append(f"Processors: load {loads}")
    bus = report["bus"]
    lines.append(f"Bus: {bus['messages']} messages, busy {bus['busy_ratio']:.1%}")
    if "lateness_s" in report:
        late = report["lateness_s"]
        lines.append(f"Lateness behind the wall clock: median {_ms(late['median'])} ms, "
                     f"p99 {_ms(late['p99'])} ms, max {_ms(late['max'])} ms")
    return "\n".join(lines)
