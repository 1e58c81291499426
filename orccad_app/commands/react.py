"""``orccad react FILE [--mission M] [--inputs F] [--jsonl]``: run the automaton alone.

One instant per script line (see :mod:`orccad_app.reactive.script`); without ``--inputs`` the
script is read from standard input. Robot-Tasks are seen through their interface: ``run X``
emits ``X.start`` and waits for the inputs ``X.good_end`` or ``X.<exception>``, so a
mission's logic is tested without the plant. Exit status 1 when the mission ends ``failed``
or ``aborted``.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from orccad_app.commands.compile import positive_int
from orccad_app.diagnostics import OrccadError
from orccad_app.pipeline import ABSTRACT, COMPOSED, compile_mission, load, select_mission
from orccad_app.reactive.compiler import DEFAULT_MAX_STATES
from orccad_app.diagnostics import SourceLocation
from orccad_app.reactive.runtime import Reactor, RelationViolation
from orccad_app.reactive.script import parse_script

__all__ = ["register"]


def register(sub) -> None:
    parser = sub.add_parser("react", help="run a mission's automaton on an input script",
                            description="Run the application automaton alone, instant by "
                                        "instant, on an input script.")
    parser.add_argument("file", help="the .orc file")
    parser.add_argument("--mission", "-m", help="the mission (default: the file's only one)")
    parser.add_argument("--inputs", "-i", help="the input script (default: standard input)")
    parser.add_argument("--jsonl", action="store_true", help="one JSON object per instant")
    parser.add_argument("--composed", action="store_true",
                        help="run the composed model (the Robot-Tasks' RTAs inlined: inputs are "
                             "their observers' events) instead of the application's view")
    parser.add_argument("--max-states", type=positive_int, default=DEFAULT_MAX_STATES,
                        help=f"state budget (default {DEFAULT_MAX_STATES})")
    parser.set_defaults(func=run)


def _read_script(path: str | None) -> tuple[str, str]:
    if path is None:
        return sys.stdin.read(), "<stdin>"
    try:
        return Path(path).read_text(encoding="utf-8"), path
    except OSError as error:
        raise OrccadError(f"{path}: cannot read: {error}") from None


def run(args: argparse.Namespace) -> int:
    source = load(args.file)
    source.print_warnings()
    view = COMPOSED if args.composed else ABSTRACT
    automaton = compile_mission(source, select_mission(source, args.mission), view=view,
                                max_states=args.max_states)
    text, name = _read_script(args.inputs)
    instants = parse_script(text, name, automaton.inputs)
    timed = any(i.time_ns is not None for i in instants)
    reactor = Reactor(automaton)
    for number, instant in enumerate(instants, start=1):
        try:
            reaction = reactor.react(instant.inputs, instant.time_ns)
        except RelationViolation as error:
            raise OrccadError(error.message, SourceLocation(name, instant.line, 1)) from None
        if args.jsonl:
            record = {"instant": number, "inputs": list(instant.inputs),
                      "outputs": list(reaction.outputs), "values": reaction.values,
                      "status": reaction.status}
            if reaction.reason is not None:
                record["reason"] = reaction.reason
            if timed:
                record["time_s"] = reactor.store.clock_ns / 1e9
            print(json.dumps(record))
        else:
            clock = f"@{reactor.store.clock_ns / 1e9:g} " if timed else ""
            outputs = " ".join(_with_value(o, reaction.values) for o in reaction.outputs)
            inputs = " ".join(instant.inputs) or "-"
            status = reaction.status + (f" {reaction.reason}" if reaction.reason else "")
            print(f"{number:>4}  {clock}{inputs:<20} -> {outputs or '-':<20} [{status}]")
    return 1 if reactor.status in ("failed", "aborted") else 0


def _with_value(name: str, values: dict) -> str:
    return f"{name}({values[name]})" if name in values else name
