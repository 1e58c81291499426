"""``orccad compile FILE [--mission M] [--format summary|json|dot] [-o OUT] [--max-states N]``."""

from __future__ import annotations

import argparse
from pathlib import Path

from orccad_app.diagnostics import OrccadError
from orccad_app.pipeline import compile_mission, load, select_mission
from orccad_app.reactive.compiler import DEFAULT_MAX_STATES
from orccad_app.reactive.export import to_dot, to_json, to_summary
from orccad_app.reactive.scxml import to_scxml
from orccad_app.verify.promela import to_promela

__all__ = ["register", "FORMATS", "emit_text", "positive_int"]

FORMATS = {"summary": to_summary, "json": to_json, "dot": to_dot, "scxml": to_scxml,
           "promela": to_promela}


def positive_int(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not a whole number") from None
    if value <= 0:
        raise argparse.ArgumentTypeError(f"'{text}' must be positive")
    return value


def register(sub) -> None:
    parser = sub.add_parser("compile", help="parse, check and compile a mission to its automaton",
                            description="Parse, check and compile a mission; print its automaton.")
    parser.add_argument("file", help="the .orc file")
    parser.add_argument("--mission", "-m", help="the mission (default: the file's only one)")
    parser.add_argument("--format", "-f", choices=sorted(FORMATS), default="summary")
    parser.add_argument("-o", "--output", help="write to this file instead of stdout")
    parser.add_argument("--max-states", type=positive_int, default=DEFAULT_MAX_STATES,
                        help=f"state budget (default {DEFAULT_MAX_STATES})")
    parser.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    source = load(args.file)
    source.print_warnings()
    automaton = compile_mission(source, select_mission(source, args.mission),
                                max_states=args.max_states)
    emit_text(FORMATS[args.format](automaton), args.output)
    return 0


def emit_text(text: str, output: str | None) -> None:
    """Print ``text``, or write it to the file ``output``."""
    if output:
        try:
            Path(output).write_text(text + "\n", encoding="utf-8")
        except OSError as error:
            raise OrccadError(f"{output}: cannot write: {error}") from None
    else:
        print(text)
