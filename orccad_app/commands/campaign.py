"""``orccad campaign FILE --spec CAMPAIGN.toml``: many runs over drawn settings; statistics.

::

    orccad campaign FILE --spec SPEC.toml [--mission M] [--runs N] [--until S]
                    [--epsilon E] [--confidence C] [--hypothesis 'P(done) >= 0.9'] [--delta D]
                    [--workers N | --cluster tcp://HOST:8786] [--db OUT.db] [--resume]
                    [--report OUT.html|DIR] [--json]

See docs/campaigns.md and :mod:`orccad_app.campaign`. Exit status: 0; 1 when the hypothesis
is rejected; 2 on bad input (the spec's errors name its line); 3 when a run crashed twice (an
internal error; the others are kept); 130 on Ctrl-C or SIGTERM (the workers are stopped, the
report of the finished runs is printed and every finished run is in the database: ``--resume``
continues).
"""

from __future__ import annotations

import argparse
import os
import sys
from contextlib import contextmanager
from typing import Iterator

from orccad_app.commands.arguments import (bounded_int, seconds,
                                           writable_output)

__all__ = ["register", "run", "add_common", "MAX_WORKERS", "MAX_RUNS"]

MAX_WORKERS = 256
"""Most local worker processes (each is a forked interpreter holding the compiled mission)."""

MAX_RUNS = 1_000_000
"""Mirrors ``campaign.spec.MAX_RUNS`` (a test keeps them equal; importing the campaign package
here would slow every command's start-up)."""


def _probability(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number, got {text!r}") from None
    if not 0 < value < 1:  # NaN fails this test too
        raise argparse.ArgumentTypeError(f"expected a number in (0, 1), got {text!r}")
    return value


def _seconds(text: str) -> float:
    return seconds(text)  # finite, in (0, one year]: docs/limits.md


def add_common(parser: argparse.ArgumentParser) -> None:
    """Options shared with ``orccad falsify``."""
    parser.add_argument("file", help="the .orc file")
    parser.add_argument("--spec", required=True, metavar="SPEC.toml",
                        help="the campaign spec (docs/campaigns.md)")
    parser.add_argument("--mission", "-m", help="the mission (default: the spec's, or the "
                                                "file's only one)")
    parser.add_argument("--until", type=_seconds, metavar="S",
                        help="simulated-time limit of each run [s] (default: the spec's "
                             "until_s, else orccad run's)")
    parser.add_argument("--workers", type=bounded_int(1, MAX_WORKERS), metavar="N",
                        help=f"local worker processes, at most {MAX_WORKERS} (default: the "
                             f"cores, {os.cpu_count()})")
    parser.add_argument("--cluster", metavar="tcp://HOST:8786",
                        help="run on this Dask scheduler instead (pip install "
                             "'orccad[cluster]')")
    parser.add_argument("--json", action="store_true", help="print the result as JSON")


def register(sub) -> None:
    parser = sub.add_parser("campaign", help="statistics of a mission over many drawn runs",
                            description="Run the mission over settings drawn from a spec "
                                        "(faults, parameters, timing, seeds) and estimate "
                                        "the probability of every outcome and property.")
    add_common(parser)
    parser.add_argument("--runs", type=bounded_int(1, MAX_RUNS), metavar="N",
                        help="number of runs (default: the spec's runs; with --epsilon, the "
                             "Chernoff-Hoeffding bound)")
    parser.add_argument("--epsilon", type=_probability, metavar="E",
                        help="sequential: stop when every interval's half-width is <= E")
    parser.add_argument("--confidence", type=_probability, default=0.95, metavar="C",
                        help="confidence of the intervals and the test (default 0.95)")
    parser.add_argument("--hypothesis", metavar="'P(EV) >= T'",
                        help="Wald's SPRT of P(EVENT) >= THETA (or <=); stops when decided")
    parser.add_argument("--delta", type=_probability, default=0.01, metavar="D",
                        help="half-width of the SPRT's indifference region (default 0.01)")
    parser.add_argument("--db", metavar="OUT.db",
                        help="the results database (default: SPEC's name with .db, here)")
    parser.add_argument("--resume", action="store_true",
                        help="continue the campaign in --db (same file and spec)")
    parser.add_argument("--report", metavar="OUT.html|DIR",
                        help="write a report: one HTML file, or a folder of PNG + Markdown")
    parser.set_defaults(func=run)


@contextmanager
def _sigterm_interrupts() -> Iterator[list[int]]:
    """While the campaign runs, SIGTERM interrupts it as Ctrl-C does (the workers stopped, the
    finished runs reported and kept); the list it yields holds the signal once received."""
    import signal
    import threading

    received: list[int] = []
    if threading.current_thread() is not threading.main_thread():
        yield received
        return

    def on_sigterm(signum: int, frame: object) -> None:
        if not received:
            received.append(signum)
            raise KeyboardInterrupt

    previous = signal.signal(signal.SIGTERM, on_sigterm)
    try:
        yield received
    finally:
        signal.signal(signal.SIGTERM, previous)


def default_db(spec_path: str) -> str:
    name = os.path.basename(spec_path)
    return (name[:-5] if name.endswith(".toml") else name) + ".db"


def run(args: argparse.Namespace) -> int:
    from orccad_app.campaign.adapter import CRASHED
    from orccad_app.campaign.output import Progress, format_result, result_dict
    from orccad_app.campaign.runner import Campaign, CampaignOptions
    from orccad_app.campaign.spec import load_spec
    from orccad_app.jsonout import dumps

    if args.report:  # written after the runs: refused now, not after hours of them
        writable_output(args.report, "--report", folder=not args.report.endswith(".html"))
    spec = load_spec(args.spec)
    options = CampaignOptions(args.runs, args.workers, args.cluster,
                              args.db or default_db(args.spec), args.resume, args.epsilon,
                              args.confidence, args.hypothesis, args.delta, args.until)
    campaign = Campaign(args.file, spec, options, args.mission)
    with _sigterm_interrupts() as terminated:
        if sys.stderr.isatty() and not args.json:
            with Progress(args.confidence) as progress:
                result = campaign.run(progress)
        else:
            result = campaign.run()
    if args.report:
        from orccad_app.campaign.report import write_report
        write_report(result, args.report)
    if args.json:
        print(dumps(result_dict(result), indent=2))
    else:
        print(format_result(result))
        if args.report:
            print(f"Report: {args.report}")
    if result.interrupted:
        why = "terminated (SIGTERM)" if terminated else "interrupted"
        print(f"orccad: {why}; continue with --resume", file=sys.stderr)
        return 130
    if any(r.status == CRASHED for r in result.records):
        print("orccad: some runs crashed twice (status 'crashed' in the database)",
              file=sys.stderr)
        return 3
    if result.sprt is not None and result.sprt["decision"] == "rejected":
        return 1
    return 0
