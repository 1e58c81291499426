"""``orccad tcs FILE --task T``: a Robot-Task's time-constrained specification, analysed.

Prints the TCS graph (text, or ``--format dot``), its coherence, per-processor utilization and
the schedulability of the executive's run under ``--scheduler fp|edf`` with
``--context-switch-us`` and ``--bus-us`` (protocol blocking, EDF's processor demand, bus
delays per message class), the static deadlock analysis (cycles of blocking protocols, named
by ports) and a placement on ``--processors N`` processors that minimizes inter-processor
traffic under ``--bound`` (see :mod:`orccad_app.tcs.report`). ``--json`` (or ``--format
json``) prints strict JSON. The task is
instantiated with its parameters' defaults (``--mission M`` and ``--site K``: with the
arguments of the K-th ``run`` of the task in that mission). Exit status 1 when the TCS is
incoherent, unschedulable or may deadlock.
"""

from __future__ import annotations

import argparse

from orccad_app.commands.arguments import (add_file, add_format, add_mission, add_output,
                                           bounded_int, emit_text, non_negative_int,
                                           refuse_overwriting)

__all__ = ["register", "run", "MAX_PROCESSORS"]

#: Most processors a placement is searched on (its cost grows with processors × modules); the
#: same figure as ``orccad_app.tcs.placement.MAX_PROCESSORS`` (not imported here: it would load
#: networkx when the parser is built).
MAX_PROCESSORS = 256


def _bound(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number, got {text!r}") from None
    if not 0 < value <= 1:  # NaN fails this test too
        raise argparse.ArgumentTypeError(f"the bound must be in (0, 1], got {text!r}")
    return value


def register(sub) -> None:
    parser = sub.add_parser("tcs", help="a Robot-Task's TCS: graph, schedulability, deadlock, "
                                        "placement",
                            description="Analyse the time-constrained specification of one "
                                        "Robot-Task.")
    add_file(parser)
    parser.add_argument("--task", "-t", required=True, help="the Robot-Task")
    add_format(parser, {"text": "the analyses, readable (default)",
                        "dot": "the TCS graph for Graphviz",
                        "json": "the analyses as one JSON document"}, "text")
    parser.add_argument("--json", action="store_true", help="same as --format json")
    parser.add_argument("--processors", "-n", type=bounded_int(1, MAX_PROCESSORS), default=2,
                        metavar="N", help="processors of the suggested placement (default 2, "
                                          f"at most {MAX_PROCESSORS})")
    parser.add_argument("--bound", type=_bound, default=1.0,
                        help="utilization bound per processor of the placement (default 1)")
    parser.add_argument("--scheduler", choices=("fp", "edf"), default="fp",
                        help="every processor's scheduler, as in 'orccad run' (default fp)")
    parser.add_argument("--context-switch-us", type=bounded_int(0, 10**9), default=0,
                        metavar="US",
                        help="context-switch overhead in the analysis [µs] (default 0)")
    parser.add_argument("--bus-us", type=bounded_int(0, 10**9), default=0, metavar="US",
                        help="transfer time of one bus message [µs] (default 0)")
    add_mission(parser, "take the task's arguments from a run of this mission")
    parser.add_argument("--site", type=non_negative_int, default=0, metavar="K",
                        help="with --mission: which run of the task (0 = first)")
    add_output(parser)
    parser.set_defaults(func=run)


def _instance(source, args: argparse.Namespace):
    from orccad_app.diagnostics import OrccadError
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


def _groups(instance, tcs) -> dict[str, int]:
    """Activation stages: measuring observers start in phase 2, the other modules in phase 3."""
    measuring = set(getattr(instance, "measuring", ()))
    return {t.name: 2 if t.name in measuring else 3 for t in tcs.module_tasks}


def run(args: argparse.Namespace) -> int:
    from orccad_app.mission.tcs_bridge import task_tcs
    from orccad_app.pipeline import load
    from orccad_app.tcs.bus_delay import BusModel
    from orccad_app.tcs.report import analyse, to_dict, to_dot, to_text

    refuse_overwriting(args.output, args.file)
    source = load(args.file)
    source.print_warnings()
    instance = _instance(source, args)
    tcs = task_tcs(instance)
    report = analyse(tcs, args.processors, args.bound, args.context_switch_us * 1000,
                     args.scheduler, BusModel(args.bus_us * 1000), _groups(instance, tcs))
    if args.format == "dot":
        text = to_dot(tcs)
    elif args.json or args.format == "json":
        from orccad_app.jsonout import dumps
        text = dumps(to_dict(report), indent=2)
    else:
        text = to_text(report)
    emit_text(text, args.output)
    return 0 if report.ok else 1
