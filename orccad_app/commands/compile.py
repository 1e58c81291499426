"""``orccad compile FILE [--mission M] [--format F] [-o OUT] [--max-states N]``."""

from __future__ import annotations

import argparse

from orccad_app.commands.arguments import (EXPORT_FORMATS, add_file, add_format, add_max_states,
                                           add_mission, add_output, emit_text, positive_int,
                                           refuse_overwriting)

__all__ = ["register", "exporter", "emit_text", "positive_int", "FORMAT_NAMES"]

#: The formats ``--format`` accepts.
FORMAT_NAMES = tuple(EXPORT_FORMATS)


def exporter(name: str):
    """The function ``Automaton -> str`` of the export format ``name``."""
    if name == "scxml":
        from orccad_app.reactive.scxml import to_scxml
        return to_scxml
    if name == "promela":
        from orccad_app.verify.promela import to_promela
        return to_promela
    from orccad_app.reactive import export
    return {"summary": export.to_summary, "json": export.to_json, "dot": export.to_dot}[name]


def register(sub) -> None:
    parser = sub.add_parser("compile", help="parse, check and compile a mission to its automaton",
                            description="Parse, check and compile a mission; print its automaton.")
    add_file(parser)
    add_mission(parser)
    add_format(parser, EXPORT_FORMATS, "summary")
    add_output(parser)
    add_max_states(parser)
    parser.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from orccad_app.pipeline import compile_mission, load, select_mission

    refuse_overwriting(args.output, args.file)
    source = load(args.file)
    source.print_warnings()
    automaton = compile_mission(source, select_mission(source, args.mission),
                                max_states=args.max_states)
    emit_text(exporter(args.format)(automaton), args.output)
    return 0
