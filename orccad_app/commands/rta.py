"""``orccad rta FILE --task T [--format F] [-o OUT] [--max-states N]``: a Robot-Task's RTA.

Prints the behaviour automaton generated for the Robot-Task (RR-1801 §3.4.3), stand-alone:
started in its first instant, ending ``done`` at its good end, ``failed`` on a type-2
exception, ``aborted`` on a type-3 one. See ``docs/robot-tasks.md`` for its signals.
"""

from __future__ import annotations

import argparse

from orccad_app.commands.arguments import (EXPORT_FORMATS, add_file, add_format, add_max_states,
                                           add_output, emit_text, refuse_overwriting)

__all__ = ["register"]


def register(sub) -> None:
    parser = sub.add_parser("rta", help="the generated behaviour automaton of a Robot-Task",
                            description="Print the behaviour automaton (RTA) generated for "
                                        "one Robot-Task.")
    add_file(parser)
    parser.add_argument("--task", "-t", required=True, help="the Robot-Task")
    add_format(parser, EXPORT_FORMATS, "summary")
    add_output(parser)
    add_max_states(parser)
    parser.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from orccad_app.commands.compile import exporter
    from orccad_app.diagnostics import OrccadError
    from orccad_app.pipeline import load
    from orccad_app.reactive.compiler import compile_program
    from orccad_app.reactive.declarations import mission_interface
    from orccad_app.robottask.rta import rta_program

    refuse_overwriting(args.output, args.file)
    source = load(args.file)
    source.print_warnings()
    task = source.program.robottask(args.task)
    if task is None:
        known = ", ".join(t.name for t in source.program.robottasks) or "none"
        raise OrccadError(f"{source.path}: no Robot-Task named '{args.task}' "
                          f"(Robot-Tasks: {known})")
    file_level = mission_interface(source.program, None)
    declared = {s.name: s for group in file_level for s in group}
    automaton = compile_program(rta_program(task, declared), max_states=args.max_states)
    emit_text(exporter(args.format)(automaton), args.output)
    return 0

