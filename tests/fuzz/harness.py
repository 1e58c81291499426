"""Run ``orccad`` in process on generated input and check the promises of docs/limits.md.

:func:`run_orccad` runs one command line with a wall-clock budget and returns what it
printed; :func:`check_outcome` asserts: no uncaught exception (no traceback, no internal
error), an exit status in {0, 1, 2}, the budget kept, and strict JSON where JSON was asked
for. A case that breaks a promise is saved with :func:`save_case` into ``corpus/``, whose
cases every test run replays.
"""

from __future__ import annotations

import atexit
import contextlib
import io
import json
import shutil
import signal
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

from orccad_app.cli import main

__all__ = ["Outcome", "run_orccad", "check_outcome", "strict_json", "save_case", "CORPUS",
           "replay", "scratch_folder"]

CORPUS = Path(__file__).resolve().parent / "corpus"


class OverBudget(BaseException):
    """Raised in the command by the alarm: it ran past its budget (a BaseException, so that
    the CLI's guard does not turn it into an internal error)."""


@dataclass
class Outcome:
    argv: list[str]
    status: int
    out: str
    err: str
    seconds: float


def scratch_folder(prefix: str) -> Path:
    """A new temporary folder for one generated case, removed when the test process ends (a
    fuzz run makes hundreds: none is left in the temporary directory)."""
    folder = Path(tempfile.mkdtemp(prefix=prefix))
    atexit.register(shutil.rmtree, folder, True)
    return folder


def _alarm(signum, frame):
    raise OverBudget


def run_orccad(argv: list[str], budget_s: float = 20.0) -> Outcome:
    """``orccad ARGV`` in this process, stopped after ``budget_s`` wall seconds."""
    out, err = io.StringIO(), io.StringIO()
    previous = signal.signal(signal.SIGALRM, _alarm)
    signal.setitimer(signal.ITIMER_REAL, budget_s)
    start = time.monotonic()
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            try:
                status = main(argv)
            except SystemExit as stop:  # argparse's usage errors
                status = stop.code if isinstance(stop.code, int) else 2
    except OverBudget:
        status = -1
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)
    return Outcome(list(argv), status, out.getvalue(), err.getvalue(),
                   time.monotonic() - start)


def _reject(constant: str):
    raise ValueError(f"non-strict JSON constant {constant}")


def strict_json(text: str):
    """Parse ``text`` as strict JSON (NaN and Infinity refused)."""
    return json.loads(text, parse_constant=_reject)


def check_outcome(outcome: Outcome, *, json_lines: bool = False, json_doc: bool = False,
                  budget_s: float = 20.0) -> None:
    """Assert the promises of docs/limits.md about one run."""
    where = f"orccad {' '.join(outcome.argv)}"
    assert outcome.status != -1, f"{where}: ran past its budget of {budget_s} s"
    assert "Traceback" not in outcome.err, f"{where}:\n{outcome.err[-3000:]}"
    assert "internal error" not in outcome.err, f"{where}:\n{outcome.err[-3000:]}"
    assert outcome.status in (0, 1, 2), f"{where}: exit status {outcome.status}"
    if outcome.status == 2:
        assert outcome.err.strip(), f"{where}: exit 2 without a message"
    if outcome.status in (0, 1) and json_lines:
        for line in outcome.out.splitlines():
            strict_json(line)
    if outcome.status in (0, 1) and json_doc and outcome.out.strip():
        strict_json(outcome.out)


def save_case(name: str, files: dict[str, str], argv: list[str]) -> Path:
    """Keep a found case in the corpus: its files and the command line (``{dir}`` stands for
    the folder holding the files, ``{root}`` for the repository)."""
    CORPUS.mkdir(exist_ok=True)
    path = CORPUS / f"{name}.json"
    path.write_text(json.dumps({"files": files, "argv": argv}, indent=1, ensure_ascii=False)
                    + "\n", encoding="utf-8")
    return path


def replay(case: Path, folder: Path) -> Outcome:
    """Run one corpus case in ``folder`` (its files written there first)."""
    data = json.loads(case.read_text(encoding="utf-8"))
    for name, text in data["files"].items():
        (folder / name).write_text(text, encoding="utf-8")
    root = str(Path(__file__).resolve().parents[2])
    argv = [arg.replace("{dir}", str(folder)).replace("{root}", root) for arg in data["argv"]]
    return run_orccad(argv)
