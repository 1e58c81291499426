"""``orccad sil FILE --lockstep``: the mission's Module-Tasks as a real controller process.

::

    orccad sil FILE [--mission M] (--lockstep | --realtime) [--until S] [--seed N]
                    [--inject SIG@T ...] [--set ROBOT.PARAM=V ...] [--timing T.M.F=MS ...]
                    [--trace OUT.csv|OUT.mcap] [--json] [--heartbeat-s S] [--build-dir DIR]

The Module-Tasks of every Robot-Task the mission runs are emitted as C
(:mod:`orccad_app.sil.emit`), compiled with the runtime library into the controller
(:mod:`orccad_app.sil.build`) and started as their own process; the plant server — this
process: the executive's timing model, the automaton and the MuJoCo plant — sends it one
request per job over a Unix socket (:mod:`orccad_app.sil.lockstep`). The report, ``--json``,
``--trace`` and ``--inject`` are ``orccad run``'s; the report adds the controller process.
A controller that crashes or misses its heartbeat (no answer within ``--heartbeat-s``) ends the
run ``failed`` with the reason; it is always killed and reaped. Exit status as ``orccad run``.
"""

from __future__ import annotations

import argparse
import math
import sys

from orccad_app.commands.arguments import (MAX_SECONDS, add_mission, checked_injection, non_negative_int,
                                           refuse_overwriting, seconds)

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
    parser.add_argument("--until", type=seconds, default=None, metavar="S",
                        help="simulated-time limit [s] (default as orccad run)")
    parser.add_argument("--seed", type=non_negative_int, default=0, metavar="N",
                        help="seed of execution times and sensor noise (default 0)")
    parser.add_argument("--inject", action="extend", nargs="+", default=[], metavar="SIG@T",
                        help="raise input SIG at simulated time T [s] (as orccad run)")
    parser.add_argument("--set", action="append", default=[], dest="overrides",
                        metavar="ROBOT.PARAM=V",
                        help="set a parameter the robot type declares (as orccad run)")
    parser.add_argument("--timing", action="append", default=[], metavar="T.M.F=MS",
                        help="set a module's period_ms, wcet_ms or bcet_ms (as orccad run)")
    parser.add_argument("--trace", metavar="OUT", help="write a trace (.csv or .mcap)")
    parser.add_argument("--json", action="store_true", help="print the report as JSON")
    parser.add_argument("--heartbeat-s", type=_heartbeat, default=None, metavar="S",
                        help="the controller must answer each request within S wall seconds "
                             "(default 10), else the run ends failed")
    parser.add_argument("--build-dir", metavar="DIR",
                        help="where the generated C goes (default: a temporary directory)")
    parser.set_defaults(func=run)


def _injections(texts: list[str], inputs) -> list:
    from orccad_app.mission.injection import typed_injections

    parsed = [checked_injection(text) for text in texts]
    return typed_injections(parsed, inputs)


def _controller(args: argparse.Namespace, plan, build_dir, heartbeat_s: float):
    """The controller of the mode (a context manager)."""
    if args.realtime:
        from orccad_app.sil.realtime import realtime

        return realtime(plan, args.file, build_dir, heartbeat_s)
    from orccad_app.sil.lockstep import lockstep

    return lockstep(plan, args.file, build_dir, heartbeat_s)


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

    from orccad_app.executive.bus import Bus
    from orccad_app.executive.processor import Processor
    from orccad_app.jsonout import dumps
    from orccad_app.mission.overrides import PlanOverrides, plan_with_overrides
    from orccad_app.mission.run import MissionRun, run_horizon_s
    from orccad_app.pipeline import load, select_mission
    from orccad_app.properties import PropertyMonitor, results_dict
    from orccad_app.properties.report import format_properties
    from orccad_app.sil.controller import DEFAULT_HEARTBEAT_S
    from orccad_app.trace import (InjectionRecord, TraceRecorder, format_report, open_trace,
                                  report_dict, sensor_ports)

    overrides = PlanOverrides.from_arguments(args.overrides, args.timing)
    refuse_overwriting(args.trace, args.file)
    source = load(args.file)
    source.print_warnings()
    mission = select_mission(source, args.mission)
    plan = plan_with_overrides(source, mission, overrides)
    injections = _injections(args.inject, plan.automaton.inputs)
    injected = [InjectionRecord(i.time_ns, i.name, i.value, i.fault) for i in injections]
    until_s = min(args.until if args.until is not None else run_horizon_s(plan, 60.0),
                  MAX_SECONDS)
    options = dict(seed=args.seed, until_ns=int(round(until_s * 1e9)), injections=injections,
                   processors=[Processor(name) for name in plan.processor_names], bus=Bus())
    build_dir = Path(args.build_dir) if args.build_dir else None
    heartbeat_s = args.heartbeat_s or DEFAULT_HEARTBEAT_S
    timings = None
    with _controller(args, plan, build_dir, heartbeat_s) as started:
        if args.realtime:
            from orccad_app.sil.realtime import RealtimeRun

            table, controller, shared = started
            mission_run: MissionRun = RealtimeRun(plan, table, controller, shared, **options)
        else:
            controller = started
            mission_run = MissionRun(plan, **options)
        monitor = PropertyMonitor(source.program, mission, mission_run)
        writer = None
        if args.trace:
            writer = open_trace(args.trace, {"mission": mission.name, "file": args.file,
                                             "seed": str(args.seed)}, sensor_ports(plan))
            mission_run.add_observer(TraceRecorder(writer))
        try:
            result = mission_run.run()
        finally:
            if writer is not None:
                writer.close()
        if args.realtime:
            timings = mission_run.timings()  # type: ignore[attr-defined]
    modules = len(plan.tcs.module_tasks)
    verdicts = monitor.results()
    if args.json:
        report = report_dict(result, injected)
        report["properties"] = results_dict(verdicts)
        report["controller"] = {"mode": "realtime" if args.realtime else "lockstep",
                                "pid": controller.pid, "module_tasks": modules}
        if timings is not None:
            report["controller"]["timing"] = [_timing_dict(t) for t in timings]
        print(dumps(report, indent=2))
    else:
        print(format_report(result, injected))
        if verdicts:
            print("\n".join(format_properties(verdicts)))
        how = ("real-time threads, the plant over shared memory" if args.realtime
               else "lockstep over a Unix socket")
        print(f"Controller: process {controller.pid}, {modules} Module-Tasks in C, {how}")
        if timings is not None:
            print("\n".join(_timing_lines(timings)))
        if args.trace:
            print(f"Trace: {args.trace}")
    if result.interrupted:
        print("orccad: interrupted", file=sys.stderr)
        return 130
    if result.status != "done" and not args.json:
        print(f"orccad: mission {result.status}: {result.reason}", file=sys.stderr)
    violated = [v.name for v in verdicts if v.verdict.value == "false"]
    return max(result.exit_status, 1 if violated else 0)
