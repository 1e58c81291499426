"""``orccad run FILE``: run a mission in the timed executive against the MuJoCo plant.

::

    orccad run FILE [--mission M] [--until S] [--seed N] [--inject SIG@T ...]
                    [--inject-from SCRIPT]
                    [--set ROBOT.PARAM=V ...] [--timing TASK.MODULE.FIELD=MS ...]
                    [--realtime [FACTOR]] [--trace OUT.csv|OUT.mcap|DIR]
                    [--trace-format csv|mcap|rosbag2] [--json]
                    [--foxglove] [--foxglove-port PORT] [--foxglove-wait S]
                    [--scheduler fp|edf] [--context-switch-us US] [--bus-us US]

The mission's automaton (application + RTAs) runs in the loop with the Module-Tasks of its
Robot-Tasks on simulated processors and the robot's plant (:mod:`orccad_app.mission.run`).
Prints a report (``--json``: one object, see :mod:`orccad_app.trace.report`) with the verdict
of every ``property`` of the mission on this run (key ``properties``, see
:mod:`orccad_app.properties`). Exit status: 0 when the mission ends ``done`` and no property
is false on the run; 1 when it ends ``failed``, ``aborted`` or ``timeout``, or a property is
false (a
deadlock, a diverging plant or a failing module is ``failed``; the report and trace are still
written); 2 on bad input; 130 on Ctrl-C (the trace stays valid, the report is printed).
"""

from __future__ import annotations

import argparse

from orccad_app.commands.arguments import add_mission, factor, refuse_overwriting
from orccad_app.commands.run_flags import (add_run_flags, check_run_flags, observe, render,
                                           refuse_trace_over_inputs, run_options)

__all__ = ["register", "run"]


def register(sub) -> None:
    parser = sub.add_parser("run", help="run a mission in the executive against the plant",
                            description="Run the mission in the timed executive (Module-Tasks "
                                        "on simulated processors, MuJoCo plant) and print a "
                                        "report.")
    parser.add_argument("file", nargs="?", metavar="FILE",
                        help="the .orc file (may also come after --inject specs)")
    add_mission(parser)
    add_run_flags(parser)
    parser.add_argument("--realtime", type=factor, nargs="?", const=1.0, metavar="FACTOR",
                        help="pace simulated time to the wall clock (× FACTOR in "
                             "[0.001, 1000], default 1) and report lateness")
    parser.set_defaults(func=run)


def _file_after_injections(args: argparse.Namespace) -> str:
    """The .orc file: the positional argument, or the word after the --inject specs that is
    not one (``orccad run --inject A@1 FILE``: a spec always holds '@')."""
    if args.file is None and args.inject and "@" not in args.inject[-1]:
        args.file = args.inject.pop()
    if args.file is None:
        from orccad_app.diagnostics import OrccadError
        raise OrccadError("orccad run: the .orc file is missing (orccad run FILE ...)")
    return args.file


def run(args: argparse.Namespace) -> int:
    from orccad_app.pipeline import load, select_mission
    from orccad_app.session import RunSession

    _file_after_injections(args)
    check_run_flags(args)
    options = run_options(args, args.realtime)
    refuse_overwriting(args.trace, args.file, flag="--trace")
    source = load(args.file)
    refuse_trace_over_inputs(args, source)
    source.print_warnings()
    with RunSession(source, select_mission(source, args.mission), options) as session:
        # a Ctrl-C before the run (a bridge opening, a Foxglove server starting) still
        # closes the trace: a complete file, or none
        starting = observe(args, session)
        report = session.execute(starting=starting)
    return render(args, report)
