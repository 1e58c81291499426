"""The ``orccad`` command.

Each sub-command lives in ``orccad_app/commands/<name>.py`` and exposes
``register(subparsers) -> None`` which adds its parser and sets ``func`` to a callable
``(args) -> int``. A command module imports only the standard library at module level (the
heavy layers are imported inside ``func``), so ``orccad --help`` starts fast.

Exit status (see ``docs/limits.md``): 0 success, 1 a checked property or the mission failed,
2 bad input (usage, parse or semantic error, unreadable or unwritable file), 3 an internal
error (a bug: a one-line message, the traceback with ``--debug`` or ``ORCCAD_DEBUG=1``),
130 interrupted (Ctrl-C). Errors never reach the user as a traceback by default.
"""

from __future__ import annotations

import os
import sys

TYPE_CHECKING = False  # not typing's: importing typing alone costs ~20 ms at every start
if TYPE_CHECKING:  # argparse is imported inside main: this module's own import is instant,
    import argparse  # so that a Ctrl-C at start-up already meets the guard of main()
    from typing import NoReturn

__all__ = ["main", "build_parser", "COMMANDS", "EXIT_INTERNAL", "EXIT_INTERRUPTED",
           "DEBUG_ENV"]

#: Sub-command modules under ``orccad_app.commands``, in the order ``--help`` lists them.
COMMANDS: tuple[str, ...] = ("compile", "check", "react", "rta", "tcs", "run", "sil", "campaign",
                             "falsify", "codegen", "tui", "lsp", "plugins")

#: Exit status of an internal error (a bug in orccad or in a plugin).
EXIT_INTERNAL = 3
#: Exit status after Ctrl-C (128 + SIGINT, as shells do).
EXIT_INTERRUPTED = 130
#: Environment variable that, set to a non-empty value other than ``0``, shows tracebacks.
DEBUG_ENV = "ORCCAD_DEBUG"

_REPORT = "please report it with the command that caused it"


def _argument_parser_class() -> type:
    import argparse

    class _ArgumentParser(argparse.ArgumentParser):
        """argparse exits 2 on usage errors already; keep its message short and clear."""

        def error(self, message: str) -> NoReturn:  # pragma: no cover - argparse plumbing
            self.print_usage(sys.stderr)
            self.exit(2, f"{self.prog}: error: {message}\n")

    return _ArgumentParser


def _version() -> str:
    from orccad_app import __version__
    return __version__


def build_parser() -> argparse.ArgumentParser:
    import argparse
    import importlib

    parser_class = _argument_parser_class()
    parser = parser_class(
        prog="orccad",
        description="Design reactive, real-time robot controllers.",
        epilog="Exit status: 0 ok, 1 a property or the mission failed, 2 bad input, "
               f"3 internal error, 130 interrupted. {DEBUG_ENV}=1 or --debug shows the "
               "traceback of an internal error.")
    parser.add_argument("--version", action="version", version=f"orccad {_version()}")
    parser.add_argument("--debug", action="store_true",
                        help="show the Python traceback of an internal error")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=parser_class)
    for name in COMMANDS:
        importlib.import_module(f"orccad_app.commands.{name}").register(sub)
    for command in sub.choices.values():  # `orccad run F --debug` works too
        command.add_argument("--debug", action="store_true", default=argparse.SUPPRESS,
                             help="show the Python traceback of an internal error")
    return parser


def _debugging(args: argparse.Namespace | None) -> bool:
    return bool(getattr(args, "debug", False)) or os.environ.get(DEBUG_ENV, "") not in ("", "0")


def _silence_stdout() -> None:
    """Point stdout at /dev/null so that the interpreter's final flush cannot fail again."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, ValueError, AttributeError):  # pragma: no cover - no real stdout
        pass


def _flush_stdout() -> None:
    """Flush stdout now, inside the guard: a full disk is reported, not lost at exit."""
    if sys.stdout is not None:
        sys.stdout.flush()


def _internal_error(error: BaseException, args: argparse.Namespace | None) -> int:
    if _debugging(args):
        import traceback
        traceback.print_exception(type(error), error, error.__traceback__, file=sys.stderr)
    detail = f"{type(error).__name__}: {error}".replace("\n", " ")
    if len(detail) > 200:
        detail = detail[:197] + "..."
    hint = "" if _debugging(args) else f" (--debug or {DEBUG_ENV}=1 shows the traceback)"
    print(f"orccad: internal error ({detail}); this is a bug, {_REPORT}{hint}",
          file=sys.stderr)
    return EXIT_INTERNAL


def _dispatch(args: argparse.Namespace) -> int:
    try:
        status = args.func(args)
    except SystemExit as exit_:  # a plugin or library called sys.exit: not ours to end with
        raise RuntimeError(f"sys.exit({exit_.code!r}) called during '{args.command}' "
                           "(by a plugin or a library)") from exit_
    _flush_stdout()
    return int(status or 0)


class _Interrupts:
    """Ctrl-C seen by the command. Python turns Ctrl-C into ``KeyboardInterrupt``, but a C
    extension being imported (MuJoCo's) turns it into ``ImportError("initialization
    failed")``, and an optional-extra check into "needs the extra": within :func:`main`, a
    Ctrl-C is recorded as it comes, so that whatever error it causes ends the command as
    interrupted (130), never as an internal error. A handler the process inherited (Ctrl-C
    ignored, or an embedding program's own) is left alone."""

    def __init__(self) -> None:
        self.seen = False
        self._installed = False

    def _on_sigint(self, signum: int, frame: object) -> None:
        self.seen = True
        raise KeyboardInterrupt

    def __enter__(self) -> _Interrupts:
        import signal
        import threading

        if threading.current_thread() is threading.main_thread() and \
                signal.getsignal(signal.SIGINT) is signal.default_int_handler:
            signal.signal(signal.SIGINT, self._on_sigint)
            self._installed = True
        return self

    def __exit__(self, *exc: object) -> None:
        if self._installed:
            import signal

            signal.signal(signal.SIGINT, signal.default_int_handler)


def _interrupted() -> int:
    print("orccad: interrupted", file=sys.stderr)
    return EXIT_INTERRUPTED


def main(argv: list[str] | None = None) -> int:
    """Run ``orccad`` with ``argv`` (default ``sys.argv[1:]``); return the exit status."""
    interrupts = _Interrupts()
    try:
        with interrupts:
            return _main(argv, interrupts)
    except KeyboardInterrupt:  # in the instants around the guard
        return _interrupted()


def _main(argv: list[str] | None, interrupts: _Interrupts) -> int:
    args = None
    try:
        from orccad_app.diagnostics import OrccadError

        parser = build_parser()
        args = parser.parse_args(argv)
        if getattr(args, "func", None) is None:
            parser.print_help(sys.stderr)
            return 2
        try:
            return _dispatch(args)
        except OrccadError as error:
            if interrupts.seen:  # an import cut by Ctrl-C, said as a missing extra
                return _interrupted()
            _flush_stdout()
            print(error.format(), file=sys.stderr)
            return error.exit_status
    except KeyboardInterrupt:
        return _interrupted()
    except BrokenPipeError:  # e.g. `orccad compile … | head`: the reader has gone
        _silence_stdout()
        return 0
    except OSError as error:  # a full disk, a closed or unwritable output
        if interrupts.seen:
            return _interrupted()
        _silence_stdout()
        where = f"{error.filename}: " if error.filename else "cannot write output: "
        print(f"orccad: error: {where}{error.strerror or error}", file=sys.stderr)
        return 2
    except Exception as error:  # noqa: BLE001 - the one top-level guard
        if interrupts.seen:  # MuJoCo's import cut by Ctrl-C: ImportError, not a bug
            return _interrupted()
        return _internal_error(error, args)


def _forget_unhandled_interrupt() -> None:
    """CPython marks a ``KeyboardInterrupt`` that escapes code run by ``exec`` of a string
    (dataclasses and namedtuples make their methods so) as unhandled, even when caught
    later, and then ends the process by SIGINT instead of with its exit status
    (Python/pythonrun.c, ``run_eval_code_obj``); running an empty string clears the mark."""
    exec("")


def entry_point() -> None:  # pragma: no cover - the console script
    """The ``orccad`` console script: ``sys.exit(main())``, Ctrl-C included."""
    try:
        status = main()
    except KeyboardInterrupt:
        status = EXIT_INTERRUPTED
    if status == EXIT_INTERRUPTED:
        _forget_unhandled_interrupt()
    sys.exit(status)


if __name__ == "__main__":  # pragma: no cover
    entry_point()
