"""``orccad lsp [--stdio] [--debounce-ms N] [--proof-budget-s S]``: the language server.

Speaks the Language Server Protocol over stdin/stdout for editors (VS Code, Neovim, Emacs,
Helix: see ``docs/editors.md``). It needs the optional extra ``lsp`` (pygls): without it the
command exits 2 saying what to install.
"""

from __future__ import annotations

import argparse
import sys

__all__ = ["register", "run", "INSTALL_HINT"]

#: What to install when pygls is missing.
INSTALL_HINT = "pip install 'orccad[lsp]'"


def _milliseconds(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a whole number of ms, got {text!r}") from None
    if not 0 <= value <= 10_000:
        raise argparse.ArgumentTypeError(f"expected a number of ms in [0, 10000], got {value}")
    return value


def _seconds(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number of seconds, got {text!r}") from None
    if not 0.1 <= value <= 3600:  # NaN fails this test too
        raise argparse.ArgumentTypeError(f"expected seconds in [0.1, 3600], got {text!r}")
    return value


def register(sub) -> None:
    parser = sub.add_parser("lsp", help="the language server for editors (stdio)",
                            description="Serve the Language Server Protocol on stdin/stdout: "
                                        "diagnostics, hover, go to definition, completion, "
                                        "outline and the proof's verdicts in your editor "
                                        "(docs/editors.md). Needs the 'lsp' extra.")
    parser.add_argument("--stdio", action="store_true",
                        help="talk over stdin/stdout (the default and only transport; "
                             "accepted because editors pass it)")
    parser.add_argument("--debounce-ms", type=_milliseconds, default=30, metavar="N",
                        help="wait after a change before analysing (default 30)")
    parser.add_argument("--proof-budget-s", type=_seconds, default=60.0, metavar="S",
                        help="wall-time budget of one proof in the editor (default 60)")
    parser.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    try:
        import lsprotocol  # noqa: F401
        import pygls  # noqa: F401
    except ImportError as error:
        print(f"orccad lsp: error: the language server needs the optional extra 'lsp' "
              f"({error.name or 'pygls'} is not installed): {INSTALL_HINT}", file=sys.stderr)
        return 2
    from orccad_app.lsp.server import serve

    return serve(args.debounce_ms / 1000, args.proof_budget_s)
