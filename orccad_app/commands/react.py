"""``orccad react FILE [--mission M] [--inputs F] [--jsonl]``: run the automaton alone.

One instant per script line (see :mod:`orccad_app.reactive.script`); without ``--inputs`` the
script is read from standard input. Robot-Tasks are seen through their interface: ``run X``
emits ``X.start``, waits for its synchronization pre-conditions, then for the inputs
``X.good_end`` (which emits its ``postcondition emit S`` signals, as ``run`` does) or
``X.<exception>``, so a mission's logic is tested without the plant. Exit status 1 when the mission ends ``failed``
or ``aborted``.
"""

from __future__ import annotations

import argparse
import sys

from orccad_app.commands.arguments import add_file, add_max_states, add_mission

__all__ = ["register"]


def register(sub) -> None:
    parser = sub.add_parser("react", help="run a mission's automaton on an input script",
                            description="Run the application automaton alone, instant by "
                                        "instant, on an input script.")
    add_file(parser)
    add_mission(parser)
    parser.add_argument("--inputs", "-i", metavar="SCRIPT",
                        help="the input script (default: standard input)")
    parser.add_argument("--jsonl", action="store_true", help="one JSON object per instant")
    parser.add_argument("--composed", action="store_true",
                        help="run the composed model (the Robot-Tasks' RTAs inlined: inputs are "
                             "their observers' events) instead of the application's view")
    add_max_states(parser)
    parser.set_defaults(func=run)


def _read_script(path: str | None) -> tuple[str, str]:
    from orccad_app.pipeline import MAX_SOURCE_BYTES, read_source

    if path is None:  # read at most the budget: a larger input is refused, not swallowed
        stream = getattr(sys.stdin, "buffer", sys.stdin)
        data = stream.read(MAX_SOURCE_BYTES + 1)
        return (read_source(data, "<stdin>") if isinstance(data, bytes) else data), "<stdin>"
    return read_source(path), path


def run(args: argparse.Namespace) -> int:
    from orccad_app.jsonout import dumps
    from orccad_app.pipeline import ABSTRACT, COMPOSED, compile_mission, load, select_mission
    from orccad_app.diagnostics import OrccadError, SourceLocation
    from orccad_app.reactive.runtime import Reactor, RelationViolation
    from orccad_app.reactive.script import parse_script
    from orccad_app.reactive.status import Status

    source = load(args.file)
    source.print_warnings()
    view = COMPOSED if args.composed else ABSTRACT
    automaton = compile_mission(source, select_mission(source, args.mission), view=view,
                                max_states=args.max_states, lazy=True)
    text, name = _read_script(args.inputs)
    instants = parse_script(text, name, automaton.inputs)
    timed = any(i.time_ns is not None for i in instants)
    clock_width = max((len(_clock(i.time_ns or 0)) for i in instants), default=0)
    input_width = max((len(_inputs(i.inputs)) for i in instants), default=0)
    input_width = max(input_width, 20)
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
            print(dumps(record))
        else:
            clock = f"{_clock(reactor.store.clock_ns):<{clock_width}} " if timed else ""
            outputs = " ".join(_with_value(o, reaction.values) for o in reaction.outputs)
            status = reaction.status + (f" {reaction.reason}" if reaction.reason else "")
            print(f"{number:>4}  {clock}{_inputs(instant.inputs):<{input_width}} -> "
                  f"{outputs or '-':<20} [{status}]")
    return 1 if reactor.status in (Status.FAILED, Status.ABORTED) else 0


def _clock(clock_ns: int) -> str:
    return f"@{clock_ns / 1e9:g}"


def _inputs(inputs: dict) -> str:
    return " ".join(_with_value(name, inputs) for name in inputs) or "-"


def _with_value(name: str, values: dict) -> str:
    """``S``, or ``S(value)`` written as a script writes it (strings quoted)."""
    value = values.get(name) if isinstance(values, dict) else None
    if value is None:
        return name
    if isinstance(value, str):
        import json
        return f"{name}({json.dumps(value, ensure_ascii=False)})"
    if isinstance(value, bool):
        return f"{name}({'true' if value else 'false'})"
    if isinstance(value, tuple):
        return f"{name}([{', '.join(map(str, value))}])"
    return f"{name}({value})"
