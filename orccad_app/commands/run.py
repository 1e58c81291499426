"""``orccad run FILE``: run a mission in the timed executive against the MuJoCo plant.

::

    orccad run FILE [--mission M] [--until S] [--seed N] [--inject SIG@T ...]
                    [--realtime [FACTOR]] [--trace OUT.csv|OUT.mcap] [--json]
                    [--scheduler fp|edf] [--context-switch-us US] [--bus-us US]

The mission's automaton (application + RTAs) runs in the loop with the Module-Tasks of its
Robot-Tasks on simulated processors and the robot's plant (:mod:`orccad_app.executive.mission_run`).
Prints a report (``--json``: one object, see :mod:`orccad_app.trace.report`). Exit status: 0
when the mission ends ``done``; 1 when it ends ``failed``, ``aborted`` or ``timeout`` (a
deadlock, a diverging plant or a failing module is ``failed``; the report and trace are still
written); 2 on bad input; 130 on Ctrl-C (the trace stays valid, the report is printed).
"""

from __future__ import annotations

import argparse
import json
import sys

__all__ = ["register", "run"]


def _seconds(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected seconds, got {text!r}") from None
    if not value > 0:
        raise argparse.ArgumentTypeError(f"expected a duration > 0 s, got {text!r}")
    return value


def _non_negative(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected an integer, got {text!r}") from None
    if value < 0:
        raise argparse.ArgumentTypeError(f"expected an integer >= 0, got {text!r}")
    return value


def register(sub) -> None:
    parser = sub.add_parser("run", help="run a mission in the executive against the plant",
                            description="Run the mission in the timed executive (Module-Tasks "
                                        "on simulated processors, MuJoCo plant) and print a "
                                        "report.")
    parser.add_argument("file", help="the .orc file")
    parser.add_argument("--mission", "-m", help="the mission (default: the file's only one)")
    parser.add_argument("--until", type=_seconds, default=None, metavar="S",
                        help="simulated-time limit [s] (default 60, or the robot type's "
                             "longer run_horizon_s); status 'timeout' if the mission is "
                             "still running then")
    parser.add_argument("--seed", type=_non_negative, default=0, metavar="N",
                        help="seed of execution times and sensor noise (default 0)")
    parser.add_argument("--inject", action="extend", nargs="+", default=[], metavar="SIG@T",
                        help="raise input SIG (or SIG(value)) at simulated time T [s]; "
                             "ROBOT.FAULT=VALUE@T applies a plant fault (auv.leak=1@120)")
    parser.add_argument("--realtime", type=_seconds, nargs="?", const=1.0, metavar="FACTOR",
                        help="pace simulated time to the wall clock (× FACTOR, default 1) and "
                             "report lateness")
    parser.add_argument("--trace", metavar="OUT", help="write a trace (.csv or .mcap)")
    parser.add_argument("--json", action="store_true", help="print the report as JSON")
    parser.add_argument("--scheduler", choices=("fp", "edf"), default="fp",
                        help="scheduling policy of every processor (default fp)")
    parser.add_argument("--context-switch-us", type=_non_negative, default=0, metavar="US",
                        help="context-switch overhead [µs] (default 0)")
    parser.add_argument("--bus-us", type=_non_negative, default=0, metavar="US",
                        help="bus transfer time per message [µs] (default 0)")
    parser.set_defaults(func=run)


def _processors(plan, args: argparse.Namespace) -> list:
    from orccad_app.executive.processor import Processor

    names = dict.fromkeys(task.processor for task in plan.tcs.module_tasks)
    return [Processor(name, args.scheduler, args.context_switch_us * 1000) for name in names]


def run(args: argparse.Namespace) -> int:
    from orccad_app.executive.bus import Bus
    from orccad_app.executive.mission_plan import plan_mission
    from orccad_app.executive.mission_run import MissionRun, parse_injection, run_horizon_s
    from orccad_app.pipeline import load, select_mission
    from orccad_app.trace import (InjectionRecord, TraceRecorder, format_report, open_trace,
                                  report_dict, sensor_ports)

    injections = [parse_injection(text) for text in args.inject]
    source = load(args.file)
    source.print_warnings()
    mission = select_mission(source, args.mission)
    plan = plan_mission(source, mission)
    writer = None
    until_s = args.until if args.until is not None else run_horizon_s(plan, 60.0)
    mission_run = MissionRun(plan, seed=args.seed, until_ns=int(round(until_s * 1e9)),
                             injections=injections, processors=_processors(plan, args),
                             bus=Bus(transfer_ns=args.bus_us * 1000), realtime=args.realtime)
    if args.trace:
        writer = open_trace(args.trace, {"mission": mission.name, "file": args.file,
                                         "seed": str(args.seed)}, sensor_ports(plan))
        mission_run.add_observer(TraceRecorder(writer))
    try:
        result = mission_run.run()
    finally:
        if writer is not None:
            writer.close()
    injected = [InjectionRecord(i.time_ns, i.name, i.value, i.fault) for i in injections]
    if args.json:
        print(json.dumps(report_dict(result, injected), indent=2))
    else:
        print(format_report(result, injected))
        if args.trace:
            print(f"Trace: {args.trace}")
    if result.interrupted:
        print("orccad: interrupted", file=sys.stderr)
        return 130
    if result.status != "done" and not args.json:
        print(f"orccad: mission {result.status}: {result.reason}", file=sys.stderr)
    return result.exit_status
