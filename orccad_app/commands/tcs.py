"""``orccad tcs FILE --task T``: a Robot-Task's time-constrained specification, analysed.

Prints the TCS graph (text, or ``--format dot``), its coherence, per-processor utilization and
the fixed-priority response-time analysis, the static deadlock analysis (cycles of blocking
protocols, named by ports) and a placement on ``--processors N`` processors that minimizes
inter-processor traffic under ``--bound`` (see :mod:`orccad_app.tcs.report`). The task is
instantiated with its parameters' defaults (``--mission M`` and ``--site K``: with the
arguments of the K-th ``run`` of the task in that mission). Exit status 1 when the TCS is
incoherent, unschedulable or may deadlock.
"""

from __future__ import annotations

import argparse
import json

from orccad_app.commands.compile import emit_text, positive_int
from orccad_app.diagnostics import OrccadError

__all__ = ["register", "run"]


def _bound(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number, got {text!r}") from None
    if not 0 < value <= 1:
        raise argparse.ArgumentTypeError(f"the bound must be in (0, 1], got {text!r}")
    return value


def register(sub) -> None:
    parser = sub.add_parser("tcs", help="a Robot-Task's TCS: graph, schedulability, deadlock, "
                                        "placement",
                            description="Analyse the time-constrained specification of one "
                                        "Robot-Task.")
    parser.add_argument("file", help="the .orc file")
    parser.add_argument("--task", "-t", required=True, help="the Robot-Task")
    parser.add_argument("--format", "-f", choices=("text", "dot", "json"), default="text")
    parser.add_argument("--processors", "-n", type=positive_int, default=2, metavar="N",
                        help="processors of the suggested placement (default 2)")
    parser.add_argument("--bound", type=_bound, default=1.0,
                        help="utilization bound per processor of the placement (default 1)")
    parser.add_argument("--context-switch-us", type=int, default=0, metavar="US",
                        help="context-switch overhead in the analysis [µs] (default 0)")
    parser.add_argument("--mission", "-m", help="take the task's arguments from a run of "
                                                "this mission")
    parser.add_argument("--site", type=int, default=0,
                        help="with --mission: which run of the task (0 = first)")
    parser.add_argument("-o", "--output", help="write to this file instead of stdout")
    parser.set_defaults(func=run)


def _instance(source, args: argparse.Namespace):
    from orccad_app.robottask.model import instantiate

    program = source.program
    task = program.robottask(args.task)
    if task is None:
        known = ", ".join(t.name for t in program.robottasks) or "none"
        raise OrccadError(f"{source.path}: no Robot-Task named '{args.task}' "
                          f"(Robot-Tasks: {known})")
    robots = {r.name: r for r in program.robots}
    if args.mission is None:
        found = source.instances.defaults.get(task.name)
        if found is None and source.host is not None:  # (instantiating it says why not)
            found = instantiate(task, robots, source.host)
        return found
    from orccad_app.pipeline import compose_mission, select_mission

    sites = compose_mission(source, select_mission(source, args.mission)).sites
    runs = [site for site in sites if site.task == task.name]
    if not 0 <= args.site < len(runs):
        raise OrccadError(f"mission '{args.mission}' runs '{task.name}' {len(runs)} time(s): "
                          f"no --site {args.site}")
    return source.instance(runs[args.site].stmt)


def run(args: argparse.Namespace) -> int:
    from orccad_app.mission.tcs_bridge import task_tcs
    from orccad_app.pipeline import load
    from orccad_app.tcs.report import analyse, to_dict, to_dot, to_text

    if args.context_switch_us < 0:
        raise OrccadError("--context-switch-us must be >= 0")
    source = load(args.file)
    source.print_warnings()
    tcs = task_tcs(_instance(source, args))
    report = analyse(tcs, args.processors, args.bound, args.context_switch_us * 1000)
    if args.format == "dot":
        text = to_dot(tcs)
    elif args.format == "json":
        text = json.dumps(to_dict(report), indent=2)
    else:
        text = to_text(report)
    emit_text(text, args.output)
    return 0 if report.ok else 1
