"""``orccad falsify FILE --spec SPEC.toml --property P``: search for the worst setting.

::

    orccad falsify FILE --spec SPEC.toml --property P [--budget N] [--sampler tpe|cmaes|random]
                   [--seed N] [--run-seed N] [--study OUT.db] [--resume] [--trace OUT]
                   [--workers N | --cluster tcp://HOST:8786] [--mission M] [--until S] [--json]

Minimizes P's robustness (a ``[[check]]`` of the spec or a property of the mission) over the
spec's space with optuna (:mod:`orccad_app.campaign.falsify`), then replays the worst setting
with a trace and prints its ``orccad run`` command. Exit status: 1 when a violating setting
was found (robustness < 0), 0 when none was; 2 on bad input.
"""

from __future__ import annotations

import argparse
import os

from orccad_app.commands.arguments import bounded_int, non_negative_int, writable_output
from orccad_app.commands.campaign import add_common

__all__ = ["register", "run", "MAX_TRIALS"]

MAX_TRIALS = 10_000
"""Mirrors ``campaign.falsify.MAX_TRIALS`` (a test keeps them equal; importing optuna's side
here would slow every command's start-up)."""


def _natural(text: str) -> int:
    return non_negative_int(text)  # one check for every command (commands/arguments.py)


def register(sub) -> None:
    parser = sub.add_parser("falsify", help="search a spec's space for a property's violation",
                            description="Minimize a property's robustness over the spec's "
                                        "settings with optuna and replay the worst one.")
    add_common(parser)
    parser.add_argument("--property", "-p", required=True, metavar="P",
                        help="a [[check]] of the spec or a property of the mission")
    parser.add_argument("--budget", type=bounded_int(1, MAX_TRIALS), default=50, metavar="N",
                        help=f"runs to spend (default 50, at most {MAX_TRIALS} with the "
                             f"trials of a resumed --study)")
    parser.add_argument("--sampler", choices=("tpe", "cmaes", "random"), default="tpe",
                        help="optuna sampler (default tpe)")
    parser.add_argument("--seed", type=_natural, default=0, metavar="N",
                        help="the sampler's seed (default 0)")
    parser.add_argument("--run-seed", type=_natural, default=0, metavar="N",
                        help="the runs' seed (noise, execution times; default 0)")
    parser.add_argument("--study", metavar="OUT.db",
                        help="keep the optuna study in this SQLite file (resumable)")
    parser.add_argument("--resume", action="store_true", help="add trials to --study")
    parser.add_argument("--trace", metavar="OUT.csv|OUT.mcap",
                        help="trace of the worst run (default falsify-P.csv)")
    parser.set_defaults(func=run)


def _check_trace(trace: str) -> None:
    from orccad_app.diagnostics import OrccadError
    from orccad_app.trace.writers import TRACE_FORMATS

    writable_output(trace, "--trace")
    suffix = os.path.splitext(trace)[1].lower()
    if suffix not in TRACE_FORMATS:
        raise OrccadError(f"--trace {trace}: unknown trace format '{suffix or '(none)'}' "
                          f"(use {' or '.join(TRACE_FORMATS)})")


def run(args: argparse.Namespace) -> int:
    from orccad_app.campaign.falsify import Falsifier, check_study_file
    from orccad_app.campaign.replay import replay_with_trace
    from orccad_app.campaign.spec import load_spec
    from orccad_app.jsonout import dumps
    from orccad_app.diagnostics import OrccadError

    if args.resume and not args.study:
        raise OrccadError("--resume needs --study FILE")
    trace = args.trace or f"falsify-{args.property}.csv"
    _check_trace(trace)  # written after the trials: refused now, not after hours of them
    spec = load_spec(args.spec)
    if args.study and os.path.lexists(args.study):
        from orccad_app.pipeline import require_regular_file

        require_regular_file(args.study)  # never a FIFO or a device opened as SQLite
        check_study_file(args.study)  # nor a campaign's database
    storage = f"sqlite:///{args.study}" if args.study else None
    falsifier = Falsifier(args.file, spec, args.property, mission=args.mission,
                          until_s=args.until, sampler=args.sampler, seed=args.seed,
                          run_seed=args.run_seed, storage=storage, resume=args.resume)
    result = falsifier.run(args.budget, args.workers, args.cluster)
    replayed = replay_with_trace(falsifier.compiled, result.best.setting, spec, trace)
    command = f"{result.replay} --trace {trace}"
    robustness = replayed.properties.get(args.property)
    violated = robustness is not None and robustness.holds is False
    if args.json:
        print(dumps({"property": args.property, "sampler": args.sampler,
                          "trials": result.trials, "robustness": result.best_robustness,
                          "violated": violated, "first_violation": result.first_violation,
                          "status": replayed.status, "outcome": replayed.outcome,
                          "setting": replayed.setting.as_dict(), "replay": command,
                          "trace": trace}, indent=2))
    else:
        if result.best_robustness is None:
            margin = "no run gave it a robustness (undefined on every run)"
        else:
            margin = f"the smallest robustness is {result.best_robustness:.4g}"
        found = (f"violated ({margin}), first at trial {result.first_violation}" if violated
                 else f"not violated: {margin}")
        print(f"Falsify {args.property} on {falsifier.compiled.name} with {args.sampler}: "
              f"{result.trials} trials; {found}\n"
              f"Worst run: {replayed.outcome} at {replayed.sim_time_s:g} s\n"
              f"Replay: {command}\nTrace: {trace}")
    return 1 if violated else 0
