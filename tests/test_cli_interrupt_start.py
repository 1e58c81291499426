"""Ctrl-C at any instant of ``orccad run``'s start (issue 34 item 9): exit status 130 and
``orccad: interrupted``, a complete trace or none, never an internal error or a traceback."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from orccad_app import cli

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture
def default_ctrl_c():
    """Python's own Ctrl-C handler, as a command started from a shell has it."""
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, previous)


@pytest.mark.parametrize("becomes", [ImportError("initialization failed"),
                                     OSError("cannot read")])
def test_an_import_cut_by_ctrl_c_is_interrupted_not_an_internal_error(
        monkeypatch, capsys, default_ctrl_c, becomes):
    """MuJoCo's C extension, cut by Ctrl-C while it is imported, raises ImportError
    ("initialization failed"): on main, 'orccad: internal error (ImportError: initialization
    failed)', exit 3 (reproduced by sending SIGINT 0.9 s into orccad run)."""
    import orccad_app.commands.run as run_command

    def importing(args) -> int:
        try:
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(5)  # the handler raises here
        except KeyboardInterrupt:
            raise becomes from None  # as a C extension's init turns it
        raise AssertionError("no Ctrl-C came")

    monkeypatch.setattr(run_command, "run", importing)
    assert cli.main(["run", "missions/arm_pid.orc"]) == 130
    err = capsys.readouterr().err
    assert err == "orccad: interrupted\n"
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler  # given back


def test_a_handler_the_process_inherited_is_left_alone(monkeypatch, capsys):
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        seen = []
        import orccad_app.commands.run as run_command

        monkeypatch.setattr(run_command, "run",
                            lambda args: seen.append(signal.getsignal(signal.SIGINT)) or 0)
        assert cli.main(["run", "missions/arm_pid.orc"]) == 0
        assert seen == [signal.SIG_IGN]
    finally:
        signal.signal(signal.SIGINT, previous)


def _interrupted_at(delay_s: float, trace: Path) -> subprocess.CompletedProcess:
    process = subprocess.Popen(
        [sys.executable, "-m", "orccad_app", "run", "missions/arm_pid.orc", "--until", "60",
         "--trace", str(trace)], cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
        text=True)
    time.sleep(delay_s)
    process.send_signal(signal.SIGINT)
    out, err = process.communicate(timeout=120)
    return subprocess.CompletedProcess(process.args, process.returncode, out, err)


@pytest.mark.parametrize("delay_s", [0.3, 0.9, 1.6, 2.6])
def test_ctrl_c_at_an_instant_of_the_start_ends_with_130_and_a_complete_trace_or_none(
        tmp_path, delay_s):
    """From the imports (MuJoCo's among them) to the run's first events; on main some of
    these instants ended with a traceback, 'internal error', or death by SIGINT (-2) after
    'orccad: interrupted' (a KeyboardInterrupt out of a dataclass's exec marks CPython's
    exit)."""
    from mcap.reader import make_reader

    trace = tmp_path / "run.mcap"
    done = _interrupted_at(delay_s, trace)
    assert done.returncode == 130, done.stderr
    assert done.stderr.rstrip().endswith("orccad: interrupted"), done.stderr
    assert "internal error" not in done.stderr and "Traceback" not in done.stderr
    if trace.exists():
        with trace.open("rb") as stream:
            assert make_reader(stream).get_summary() is not None  # finished, readable
