"""``orccad tui [FILE] [--mission M] [--run] [--speed F|max] [--seed N] [--spec S | --db D]``:
the terminal UI.

Browse ``missions/`` and FILE (source with diagnostics, compile summary, ``orccad check``),
run a mission live (speed control, Robot-Tasks and phases, automaton state, log, plots,
processor load, the mission's inputs on keys 1–9), read its report and export its trace.
Textual is imported here, inside the command, so the core never imports it.
"""

from __future__ import annotations

import argparse

from orccad_app.commands.arguments import FACTOR_RANGE, add_mission, non_negative_int

__all__ = ["register", "run"]


def _speed(text: str) -> float | None:
    if text == "max":
        return None
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a factor or 'max', got {text!r}") from None
    low, high = FACTOR_RANGE
    if not low <= value <= high:  # NaN and infinities fail this test too
        raise argparse.ArgumentTypeError(f"expected a factor in [{low:g}, {high:g}] or 'max', "
                                         f"got {text!r}")
    return value


def register(sub) -> None:
    parser = sub.add_parser("tui", help="the terminal UI: browse, check and run missions live",
                            description="The mission runner: browse missions, check them, "
                                        "run them live and steer them with their inputs.")
    parser.add_argument("file", nargs="?", help="a .orc file or a folder (missions/ is "
                                                "always listed)")
    add_mission(parser, "the mission to run (with --run)")
    parser.add_argument("--run", action="store_true", help="start running FILE at once")
    parser.add_argument("--speed", type=_speed, default=1.0, metavar="F|max",
                        help="initial speed: simulated seconds per wall second, or 'max' "
                             "(default 1)")
    parser.add_argument("--seed", type=non_negative_int, default=0, metavar="N",
                        help="seed of the runs (default 0)")
    parser.add_argument("--spec", metavar="SPEC.toml",
                        help="open the campaign screen for FILE with this campaign spec")
    parser.add_argument("--db", metavar="CAMPAIGN.db",
                        help="open the campaign screen on this campaign database")
    parser.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from pathlib import Path

    from orccad_app.diagnostics import OrccadError

    paths = [args.file] if args.file else []
    if args.file and not Path(args.file).exists():
        raise OrccadError(f"{args.file}: no such file or folder")
    if args.file and not Path(args.file).is_dir():
        from orccad_app.pipeline import require_regular_file

        require_regular_file(args.file)  # a FIFO would block, /dev/zero never end
    from orccad_app.tui.app import OrccadApp  # Textual only now: the core never imports it

    selected = args.file if args.file and Path(args.file).is_file() else None
    for option, value in (("--spec", args.spec), ("--db", args.db)):
        if value is not None:
            from orccad_app.pipeline import require_regular_file

            try:
                require_regular_file(value)  # a FIFO would block the screen's first read
            except OrccadError as error:
                raise OrccadError(f"{option} {error.message}") from None
    if args.spec and selected is None:
        raise OrccadError("--spec needs the mission FILE")
    if args.run and (args.spec or args.db):
        raise OrccadError("--run and --spec/--db: choose a live run or the campaign screen")
    campaign = {"spec": args.spec, "db": args.db} if args.spec or args.db else None
    app = OrccadApp(paths, selected=selected, mission=args.mission, speed=args.speed,
                    seed=args.seed, run_now=args.run and selected is not None,
                    campaign=campaign)
    app.run()
    return 0
