"""``orccad check FILE [--mission M] [--observe S1,S2,…] [--counterexample OUT] [--promela OUT]
[--replay PROPERTY] [--json]``.

Parses and checks the file, compiles each mission (or the one named) in the composed view,
then proves the built-in properties and every ``property`` that applies to it (see
``docs/verification.md``). A failed property prints a counterexample as an input script for
``orccad react --composed``. ``--observe`` prints the automaton reduced to some signals
(observational equivalence) instead. Exit status: 0 all hold, 1 a property fails, 2 bad
input. ``--replay PROPERTY`` prints that property's counterexample instant by instant (inputs,
outputs, the statements the mission waits at, the instant where it fails) and, with
``--counterexample OUT``, writes its script for ``orccad run --inject-from OUT``. Signal properties (Signal Temporal Logic) are listed as not proved: ``orccad run``
and campaigns judge them; they do not change the exit status. ``--json`` prints the verdicts
as one object instead (each counterexample with its instants and the sub-mission instances
the mission is in after each).
"""

from __future__ import annotations

import argparse
import shlex
import sys

from orccad_app.diagnostics import OrccadError
from orccad_app.commands.arguments import (add_file, add_max_states, add_mission, emit_text,
                                           refuse_overwriting)

__all__ = ["register"]


def register(sub) -> None:
    parser = sub.add_parser("check", help="prove a mission's properties (model checking)",
                            description="Check every property of a mission, and the built-in "
                                        "ones, on its composed automaton; print a "
                                        "counterexample script for each that fails.")
    add_file(parser)
    add_mission(parser, "the mission (default: every mission)")
    parser.add_argument("--observe", metavar="S1,S2,…",
                        help="print the automaton reduced to these signals (hidden moves "
                             "abstracted, minimized by observational equivalence)")
    parser.add_argument("--counterexample", metavar="OUT",
                        help="write the first counterexample script to this file")
    parser.add_argument("--promela", metavar="OUT",
                        help="write the model and its properties in Promela (for SPIN)")
    parser.add_argument("--replay", metavar="PROPERTY",
                        help="print this property's counterexample instant by instant (inputs, "
                             "outputs, where the mission waits, where it fails); with "
                             "--counterexample OUT, write its script (for orccad run "
                             "--inject-from OUT)")
    parser.add_argument("--json", action="store_true",
                        help="print the verdicts and counterexamples as one JSON object")
    parser.add_argument("--engine", choices=("auto", "explicit", "symbolic"), default="auto",
                        help="explicit: tabulate the automaton and its model; symbolic: the "
                             "mission's circuit on BDDs (many parallel robots); auto "
                             "(default): explicit while the automaton has at most 2000 "
                             "transitions, else symbolic (docs/verification.md)")
    add_max_states(parser)
    parser.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from orccad_app.pipeline import load, require_missions, select_mission

    if args.promela and args.engine == "symbolic":
        raise OrccadError("--promela writes the explicit model: drop --engine symbolic")
    refuse_overwriting(args.counterexample, args.file)
    refuse_overwriting(args.promela, args.file)
    _refuse_json_with_text_views(args)
    source = load(args.file)
    source.print_warnings()
    missions = ([select_mission(source, args.mission)] if args.mission
                else list(require_missions(source)))
    if args.observe is not None:
        return _observe(source, missions, args)
    if args.replay is not None:
        return _replay(source, missions, args)
    failed, written, unproved = 0, False, 0
    reports = []
    for mission in missions:
        engine = "explicit" if args.promela else args.engine
        report = _checked(source, mission, args.max_states, engine)
        unproved += len(report.signal_properties)
        if args.promela:
            _write_promela(source, mission, report, args.promela)
        if args.json:
            reports.append(report)
        else:
            _print_report(source, report, len(missions) > 1)
        for outcome in report.outcomes:
            if not outcome.holds:
                failed += 1
                if args.counterexample and not written:
                    emit_text(_script_text(source, mission, outcome).rstrip("\n"),
                              args.counterexample)
                    written = True
    if args.json:
        from orccad_app.jsonout import dumps
        print(dumps({"file": source.path, "missions": [_report_dict(source, r) for r in reports],
                     "failed": failed, "holds": not failed}, indent=2))
        return 1 if failed else 0
    total = len(missions)
    left = (f"; {unproved} signal propert{'ies' if unproved > 1 else 'y'} left to runs"
            if unproved else "")
    print(f"{'all properties hold' if not failed else f'{failed} failed'} "
          f"({total} mission{'s' if total > 1 else ''}{left})")
    return 1 if failed else 0


#: Wall time [s] a check runs before its progress line appears, and between two updates.
PROGRESS_DELAY_S, PROGRESS_INTERVAL_S = 1.0, 0.5


class _Progress:
    """``check`` on a terminal past a second: states explored, then properties done, on one
    line of stderr erased before the mission's report."""

    def __init__(self, mission: str) -> None:
        from orccad_app.mission.progress import StatusLine

        self.mission = mission
        self.line = StatusLine(sys.stderr, delay_s=PROGRESS_DELAY_S,
                               interval_s=PROGRESS_INTERVAL_S)

    def states(self, explored: int) -> None:
        if self.line.due():
            self.line.show(f"checking {self.mission}: compiling, {explored} states explored")

    def properties(self, done: int, total: int) -> None:
        if self.line.due():
            self.line.show(f"checking {self.mission}: {done} of {total} properties done")


def _checked(source, mission, max_states: int, engine: str = "auto"):
    """The report of ``mission``, with a progress line when stderr is a terminal."""
    from orccad_app.verify.checker import check_mission

    if not sys.stderr.isatty():  # never in a pipe or a file
        return check_mission(source.program, mission, max_states=max_states, engine=engine)
    progress = _Progress(mission.name)
    try:
        return check_mission(source.program, mission, max_states=max_states,
                             progress=progress, engine=engine)
    finally:
        progress.line.close()


def _replay_command(source, mission) -> str:
    return (f"orccad react {shlex.quote(source.path)} --mission {mission.name} --composed "
            "--inputs SCRIPT")


def _script_text(source, mission, outcome) -> str:
    header = [f"counterexample to {outcome.kind} {mission.name}.{outcome.name}: "
              f"{outcome.message}",
              f"replay: {_replay_command(source, mission)}"]
    if outcome.script.note:
        header.append(f"note: {outcome.script.note}")
    return outcome.script.text(header)


def _print_report(source, report, several: bool) -> None:
    print(report.summary())
    for outcome in report.outcomes:
        mark = "ok  " if outcome.holds else "FAIL"
        detail = f": {outcome.message}" if outcome.message else ""
        print(f"  {mark}  {outcome.kind} {outcome.name}{detail}")
        if not outcome.holds and outcome.script is not None:
            for line in _script_text(source, report.composition.mission, outcome).splitlines():
                print(f"        | {line}")
    for prop in report.signal_properties:
        print(f"  --    signal property {prop.name}: not proved (Signal Temporal Logic); "
              "judged on runs and campaigns")


def _report_dict(source, report) -> dict:
    """One mission's verdicts, JSON-ready (no timings: the same input gives the same text)."""
    mission = report.composition.mission
    return {
        "mission": report.composition.name,
        "engine": report.engine,
        "automaton_states": report.automaton_states,
        "model_states": report.model_states,
        "model_steps": report.model_steps,
        "counters_exact": report.counters_exact,
        "outcomes": [{"kind": o.kind, "name": o.name, "holds": o.holds, "message": o.message,
                      "counterexample": None if o.holds or o.script is None else
                      _script_dict(source, mission, o)} for o in report.outcomes],
        "signal_properties": [p.name for p in report.signal_properties],
    }


def _script_dict(source, mission, outcome) -> dict:
    script = outcome.script
    return {
        "replay": _replay_command(source, mission),
        "note": script.note or None,
        "replayed": script.replayed,
        "loop_start": script.loop_start,
        "instants": [{"time_s": None if line.time_ns is None else line.time_ns / 1e9,
                      "inputs": dict(line.inputs),
                      "inside": [where.to_dict() for where in line.inside]}
                     for line in script.lines],
        "script": _script_text(source, mission, outcome),
    }


def _refuse_json_with_text_views(args: argparse.Namespace) -> None:
    """``--replay`` and ``--observe`` print text: with ``--json`` the output would not parse."""
    from orccad_app.diagnostics import OrccadError

    hints = {"--replay": " (without --replay, --json gives each counterexample with its "
                         "instants)", "--observe": ""}
    for flag, value in (("--replay", args.replay), ("--observe", args.observe)):
        if args.json and value is not None:
            raise OrccadError(f"{flag} prints text, not JSON: drop --json{hints[flag]}")


def _replay(source, missions, args) -> int:
    """``--replay PROPERTY``: exit 1 with its counterexample, 0 when it holds."""
    from orccad_app.diagnostics import OrccadError
    from orccad_app.verify.checker import check_mission
    from orccad_app.verify.replay import format_replay, replay

    wanted = args.replay.strip()
    known = []
    for mission in missions:
        name = wanted.split(".", 1)[1] if wanted.startswith(f"{mission.name}.") else wanted
        report = check_mission(source.program, mission, max_states=args.max_states,
                               engine=args.engine)
        known += [o.name for o in report.outcomes]
        outcome = next((o for o in report.outcomes if o.name == name), None)
        if outcome is None:
            continue
        if outcome.holds:
            print(f"{outcome.kind} {mission.name}.{outcome.name} holds: no counterexample")
            return 0
        print(format_replay(replay(report.composition, outcome), source.path, source.text))
        if args.counterexample:
            emit_text(_script_text(source, mission, outcome).rstrip("\n"), args.counterexample)
            print(f"run it against the plant: orccad run {shlex.quote(source.path)} --mission "
                  f"{mission.name} --inject-from {shlex.quote(args.counterexample)}")
        else:
            print("write its script with --counterexample OUT, then run it against the plant: "
                  f"orccad run {shlex.quote(source.path)} --mission {mission.name} "
                  "--inject-from OUT")
        return 1
    raise OrccadError(f"--replay {wanted}: no such property (properties: "
                      f"{', '.join(dict.fromkeys(known)) or 'none'})")


def _write_promela(source, mission, report, path: str) -> None:
    from orccad_app.verify.checker import applicable
    from orccad_app.verify.promela import to_promela

    text = to_promela(report.model.automaton, report.model.composition.roles,
                      tracked=report.model.tracked,
                      properties=[p for p in applicable(source.program.properties, mission)
                                  if p not in report.signal_properties],
                      assumptions=applicable(source.program.assumptions, mission))
    emit_text(text.rstrip("\n"), path)


def _observe(source, missions, args) -> int:
    from orccad_app.robottask.composition import compose
    from orccad_app.verify.model import build_model
    from orccad_app.verify.quotient import format_quotient, observe

    names = [n.strip() for n in args.observe.split(",") if n.strip()]
    if not names:
        from orccad_app.diagnostics import OrccadError
        raise OrccadError("--observe needs at least one signal name")
    for mission in missions:
        model = build_model(compose(source.program, mission, max_states=args.max_states))
        print(format_quotient(observe(model, names), mission.name))
    sys.stdout.flush()
    return 0
