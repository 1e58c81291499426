"""The ``orccad`` command.

Each sub-command lives in ``orccad_app/commands/<name>.py`` and exposes
``register(subparsers) -> None`` which adds its parser and sets ``func`` to a callable
``(args) -> int``. Exit status: 0 success, 1 a checked property or the mission failed,
2 bad input (usage, parse or semantic error). Errors never reach the user as a traceback.
"""

from __future__ import annotations

import argparse
import importlib
import sys

from orccad_app import __version__
from orccad_app.diagnostics import OrccadError

__all__ = ["main", "COMMANDS"]

#: Sub-command modules under ``orccad_app.commands``, in the order ``--help`` lists them.
COMMANDS: tuple[str, ...] = ("compile", "check", "react", "rta", "tcs", "run", "campaign",
                             "falsify", "tui", "plugins")


class _ArgumentParser(argparse.ArgumentParser):
    """argparse exits 2 on usage errors already; keep its message short and clear."""

    def error(self, message: str) -> None:  # pragma: no cover - argparse plumbing
        self.print_usage(sys.stderr)
        self.exit(2, f"{self.prog}: error: {message}\n")


def build_parser() -> argparse.ArgumentParser:
    parser = _ArgumentParser(
        prog="orccad",
        description="Design reactive, real-time robot controllers.",
    )
    parser.add_argument("--version", action="version", version=f"orccad {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_ArgumentParser)
    for name in COMMANDS:
        importlib.import_module(f"orccad_app.commands.{name}").register(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    if getattr(args, "func", None) is None:
        parser.print_help(sys.stderr)
        return 2
    try:
        return int(args.func(args) or 0)
    except OrccadError as error:
        print(error.format(), file=sys.stderr)
        return error.exit_status
    except KeyboardInterrupt:
        print("orccad: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:  # pragma: no cover - e.g. `orccad compile … | head`
        return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
