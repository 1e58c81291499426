"""``orccad sil FILE --lockstep | --realtime``: the mission's Module-Tasks as a real
controller process.

::

    orccad sil FILE [--mission M] (--lockstep | --realtime) [--heartbeat-s S] [--build-dir DIR]
                    [every flag of orccad run but its --realtime FACTOR]

The Module-Tasks of every Robot-Task the mission runs are emitted as C
(:mod:`orccad_app.sil.emit`), compiled with the runtime library into the controller
(:mod:`orccad_app.sil.build`) and started as their own process. The run goes through the run
façade as ``orccad run``'s does (:class:`~orccad_app.sil.runs.ControllerRuns` makes its
MissionRun), so the report, ``--json``, ``--trace``, ``--inject``, ``--inject-from``, ``--set``,
``--timing``, ``--foxglove`` and ``--ros2-zenoh`` are ``orccad run``'s; ``--scheduler``,
``--context-switch-us`` and ``--bus-us`` apply in lockstep (the executive's timing model) and
are refused in real time with the reason. The report adds the controller process (and in real
time the measured timing beside ``orccad tcs``'s bounds). A controller that crashes or misses
its heartbeat (no answer within ``--heartbeat-s``) ends the run ``failed`` with the reason; it
is always killed and reaped. Exit status as ``orccad run``.
"""

from __future__ import annotations

import argparse
import math
from typing import Any

from orccad_app.commands.arguments import add_mission, refuse_overwriting
from orccad_app.commands.run_flags import (add_run_flags, check_run_flags, observe, render,
                                           run_options)

__all__ = ["register", "run"]


def _heartbeat(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not 0.01 <= value <= 3600:
        raise argparse.ArgumentTypeError(f"expected seconds in [0.01, 3600], got {text!r}")
    return value


def register(sub) -> None:
    parser = sub.add_parser("sil", help="run the mission's Module-Tasks as a C controller "
                                        "process against the plant",
                            description="Software in the loop: the Module-Tasks emitted as C, "
                                        "compiled and run in their own process against the "
                                        "MuJoCo plant.")
    parser.add_argument("file", metavar="FILE", help="the .orc file")
    add_mission(parser)
    mode = parser.add_mutually_exclusive_group(required=True)
    mode.add_argument("--lockstep", action="store_true",
                      help="one exchange per job over a Unix socket; the plant advances by "
                           "the declared execution times (reproducible)")
    mode.add_argument("--realtime", action="store_true",
                      help="real threads per processor, wall-clock periods "
                           "(clock_nanosleep, SCHED_FIFO where permitted), the plant over "
                           "shared memory; the report adds the measured release lateness")
    add_run_flags(parser)
    parser.add_argument("--heartbeat-s", type=_heartbeat, default=None, metavar="S",
                        help="the controller must answer each request within S wall seconds "
                             "(default 10), else the run ends failed")
    parser.add_argument("--build-dir", metavar="DIR",
                        help="where the generated C goes (default: a temporary directory)")
    parser.set_defaults(func=run)


def _timing_dict(timing) -> dict:
    lateness = timing.lateness_s
    return {"module": timing.name, "released": timing.released,
            "lateness_s": None if lateness is None else
            {"median": lateness[0], "p99": lateness[1], "max": lateness[2]},
            "overruns": timing.overruns, "deadline_misses": timing.deadline_misses,
            "response_time_max_s": timing.response_max_s,
            "tcs_response_time_s": timing.predicted_s}


def _timing_lines(timings) -> list[str]:
    lines = ["Measured on the controller's threads (release lateness [µs]: median / p99 / "
             "max), beside orccad tcs's response-time bound:",
             f"  {'Module-Task':<28} {'jobs':>6} {'lateness':>24} {'overruns':>8} "
             f"{'misses':>6} {'R measured':>11} {'R tcs':>9}"]
    for t in timings:
        late = "—" if t.lateness_s is None else " / ".join(f"{v * 1e6:.0f}"
                                                           for v in t.lateness_s)
        predicted = "—" if t.predicted_s is None else f"{t.predicted_s * 1e3:.3f} ms"
        lines.append(f"  {t.name:<28} {t.released:>6} {late:>24} {t.overruns:>8} "
                     f"{t.deadline_misses:>6} {t.response_max_s * 1e3:>8.3f} ms {predicted:>9}")
    return lines


def run(args: argparse.Namespace) -> int:
    from pathlib import Path

    from orccad_app.pipeline import load, select_mission
    from orccad_app.session import RunSession
    from orccad_app.sil.controller import DEFAULT_HEARTBEAT_S
    from orccad_app.sil.runs import ControllerRuns, SilMode, refuse_in_realtime

    check_run_flags(args)
    mode = SilMode.REALTIME if args.realtime else SilMode.LOCKSTEP
    with ControllerRuns(mode, args.file, Path(args.build_dir) if args.build_dir else None,
                        args.heartbeat_s or DEFAULT_HEARTBEAT_S) as runs:
        options = run_options(args, None, runs)
        if mode is SilMode.REALTIME:
            refuse_in_realtime(options)
        refuse_overwriting(args.trace, args.file)
        source = load(args.file)
        source.print_warnings()
        session = RunSession(source, select_mission(source, args.mission), options)
        report = session.execute(starting=observe(args, session))
        timings = runs.timings()
    assert runs.controller is not None
    modules = len(session.plan.tcs.module_tasks)
    controller: dict[str, Any] = {"mode": mode.value, "pid": runs.controller.pid,
                                  "module_tasks": modules}
    how = ("real-time threads, the plant over shared memory" if timings is not None
           else "lockstep over a Unix socket")
    lines = [f"Controller: process {runs.controller.pid}, {modules} Module-Tasks in C, {how}"]
    if timings is not None:
        controller["timing"] = [_timing_dict(t) for t in timings]
        lines += _timing_lines(timings)
    return render(args, report, {"controller": controller}, tuple(lines))
