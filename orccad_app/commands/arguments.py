"""Arguments shared by the sub-commands: the same flags, the same checks, the same messages.

Every number a user types on the command line is checked here, at the boundary: finite, in
its documented range (``docs/limits.md``), else a usage error (exit status 2) naming the
flag and the range. Only the standard library is imported, so building the parser is fast.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
from pathlib import Path

__all__ = ["positive_int", "non_negative_int", "seconds", "factor", "add_file",
           "add_mission", "add_output", "add_max_states", "add_format", "emit_text",
           "refuse_overwriting", "writable_output", "DEFAULT_MAX_STATES", "MAX_SECONDS",
           "MAX_INT_ARGUMENT",
           "EXPORT_FORMATS"]

#: The compiler's default state budget (mirrors ``reactive.compiler.DEFAULT_MAX_STATES``,
#: which a test keeps equal; importing the compiler here would slow every command down).
DEFAULT_MAX_STATES = 20_000
#: Longest simulated time a command accepts [s]: one year (as durations in the language).
MAX_SECONDS = 365 * 24 * 3600.0
#: Largest whole number accepted for counts and budgets (--max-states, --seed, --site).
MAX_INT_ARGUMENT = 2**63 - 1

#: Output formats of an automaton (``compile`` and ``rta``), with their help.
EXPORT_FORMATS: dict[str, str] = {
    "summary": "states and transitions, readable (default)",
    "json": "the automaton as one JSON document",
    "dot": "a Graphviz graph",
    "scxml": "W3C SCXML state chart",
    "promela": "a Promela model for SPIN",
}


def _whole(text: str) -> int:
    try:
        value = int(text.strip().replace("_", ""), 10)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not a whole number") from None
    if abs(value) > MAX_INT_ARGUMENT:
        raise argparse.ArgumentTypeError(f"'{text}' is out of range (at most "
                                         f"{MAX_INT_ARGUMENT})")
    return value


def positive_int(text: str) -> int:
    """A whole number > 0."""
    value = _whole(text)
    if value <= 0:
        raise argparse.ArgumentTypeError(f"'{text}' must be positive")
    return value


def non_negative_int(text: str) -> int:
    """A whole number >= 0."""
    value = _whole(text)
    if value < 0:
        raise argparse.ArgumentTypeError(f"expected an integer >= 0, got {text!r}")
    return value


def bounded_int(low: int, high: int):
    """An argparse type: a whole number in ``[low, high]``."""
    def parse(text: str) -> int:
        value = _whole(text)
        if not low <= value <= high:
            raise argparse.ArgumentTypeError(f"expected a whole number in [{low}, {high}], "
                                             f"got {text!r}")
        return value
    parse.__name__ = "integer"
    return parse


def _finite(text: str, what: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected {what}, got {text!r}") from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"expected {what}, got {text!r} (not finite)")
    return value


def seconds(text: str) -> float:
    """A simulated duration [s]: finite, > 0 and at most one year."""
    value = _finite(text, "seconds")
    if not 0 < value <= MAX_SECONDS:
        raise argparse.ArgumentTypeError(f"expected a duration in (0, {MAX_SECONDS:.0f}] s "
                                         f"(one year), got {text!r}")
    return value


def delay_us(text: str) -> int:
    """A controller's delay given in µs (``--exchange-us``, ``--jitter-us``): finite, in
    [0, 1e6]; returned in whole nanoseconds."""
    value = _finite(text, "microseconds")
    if not 0 <= value <= 1e6:
        raise argparse.ArgumentTypeError(f"expected microseconds in [0, 1000000], got {text!r}")
    return int(round(value * 1000))


#: Range of pacing and speed factors (simulated s per wall s).
FACTOR_RANGE = (1e-3, 1e3)


def factor(text: str) -> float:
    """A pacing factor (simulated s per wall s) in ``FACTOR_RANGE``."""
    value = _finite(text, "a factor")
    low, high = FACTOR_RANGE
    if not low <= value <= high:
        raise argparse.ArgumentTypeError(f"expected a factor in [{low:g}, {high:g}], "
                                         f"got {text!r}")
    return value


def add_file(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("file", help="the .orc file")


def add_mission(parser: argparse.ArgumentParser, help: str | None = None) -> None:
    parser.add_argument("--mission", "-m", metavar="M",
                        help=help or "the mission (default: the file's only one)")


def add_output(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("-o", "--output", metavar="OUT",
                        help="write to this file instead of standard output")


def add_max_states(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--max-states", type=positive_int, default=DEFAULT_MAX_STATES,
                        metavar="N",
                        help=f"state budget of the compiler (default {DEFAULT_MAX_STATES})")


def add_format(parser: argparse.ArgumentParser, formats: dict[str, str], default: str) -> None:
    listing = "; ".join(f"{name}: {text}" for name, text in formats.items())
    parser.add_argument("--format", "-f", choices=list(formats), default=default,
                        help=f"output format ({listing})")


def refuse_overwriting(output: str | None, *inputs: str | None,
                       flag: str = "-o/--output") -> None:
    """Refuse ``-o OUT`` (or the output ``flag`` names) when OUT is one of the command's
    input files."""
    if not output:
        return
    from orccad_app.diagnostics import OrccadError

    target = Path(output)
    for source in inputs:
        if source and _same_file(target, Path(source)):
            raise OrccadError(f"{output}: refusing to overwrite the input file {source} "
                              f"(choose another {flag})")


def writable_output(path: str, flag: str, *, folder: bool = False) -> None:
    """Refuse, before any work, an output the command could not write at its end: a file
    (``folder=False``) whose folder is missing or read-only, or that is a folder, a FIFO or a
    device; a folder (``folder=True``, created with its parents) where a file is, or below a
    file or a read-only folder. (A campaign's ``--report`` and a falsification's ``--trace``
    are written after every run: refused then, the runs' hours would be lost.)"""
    import stat

    from orccad_app.diagnostics import OrccadError

    target = Path(path)
    try:
        mode = os.stat(target).st_mode
    except (FileNotFoundError, NotADirectoryError):
        mode = None
    except OSError as error:
        raise OrccadError(f"{flag} {path}: cannot write: {error.strerror or error}") from None
    if mode is not None:
        if folder and not stat.S_ISDIR(mode):
            raise OrccadError(f"{flag} {path}: not a folder (a report folder, or a file "
                              f"ending in .html)")
        if not folder and stat.S_ISDIR(mode):
            raise OrccadError(f"{flag} {path}: is a folder, not a file")
        if not folder and not stat.S_ISREG(mode):
            raise OrccadError(f"{flag} {path}: not a regular file (a FIFO or a device)")
        if not os.access(target, os.W_OK):
            raise OrccadError(f"{flag} {path}: cannot write: permission denied")
        return
    parent = target.absolute().parent
    while folder and not parent.exists() and parent != parent.parent:
        parent = parent.parent  # a report folder is created with its parents
    if not parent.is_dir():
        missing = "not a folder" if parent.exists() else "no such folder"
        raise OrccadError(f"{flag} {path}: cannot write: {parent}: {missing}")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise OrccadError(f"{flag} {path}: cannot write in {parent}: permission denied")


def _same_file(a: Path, b: Path) -> bool:
    try:
        return a.exists() and b.exists() and os.path.samefile(a, b)
    except OSError:
        return False


def emit_text(text: str, output: str | None) -> None:
    """Print ``text``, or write it to the file ``output``."""
    if output:
        from orccad_app.diagnostics import OrccadError
        try:
            Path(output).write_text(text + "\n", encoding="utf-8")
        except OSError as error:
            raise OrccadError(f"{output}: cannot write: {error.strerror or error}") from None
    else:
        sys.stdout.write(text + "\n")


def checked_injection(text: str):
    """``--inject`` text → :class:`Injection`, its time checked finite and within a year."""
    from orccad_app.diagnostics import OrccadError
    from orccad_app.mission.injection import parse_injection

    when = text.rpartition("@")[2]
    try:
        time_s = float(when)
    except ValueError:
        time_s = 0.0  # parse_injection names the problem
    if not (time_s == time_s and abs(time_s) <= MAX_SECONDS):
        raise OrccadError(f"bad injection {text!r}: the time must be a number of seconds in "
                          f"[0, {MAX_SECONDS:.0f}] (one year)")
    return parse_injection(text)
