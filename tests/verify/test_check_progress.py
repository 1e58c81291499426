"""``orccad check`` shows its progress (states explored, properties done) on a terminal, on
one line of stderr erased before the report; never in a pipe."""

from __future__ import annotations

import io

from orccad_app.cli import build_parser
from orccad_app.commands import check as check_command
from orccad_app.pipeline import load, select_mission
from orccad_app.verify.checker import check_mission

from .conftest import ROOT
from .test_check_cli import orccad


class Recorder:
    def __init__(self) -> None:
        self.explored: list[int] = []
        self.done: list[tuple[int, int]] = []

    def states(self, explored: int) -> None:
        self.explored.append(explored)

    def properties(self, done: int, total: int) -> None:
        self.done.append((done, total))


def test_check_mission_reports_states_explored_then_properties_done():
    source = load(ROOT / "missions" / "arm_recovery.orc")
    recorder = Recorder()
    report = check_mission(source.program, select_mission(source, None), progress=recorder)
    assert recorder.explored == list(range(1, len(recorder.explored) + 1))
    assert len(recorder.explored) >= report.composition.automaton.state_count
    total = len(report.outcomes)
    assert recorder.done == [(n, total) for n in range(1, total + 1)]


class Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


def test_on_a_terminal_the_line_is_shown_then_erased(monkeypatch, capsys):
    terminal = Terminal()
    monkeypatch.setattr("sys.stderr", terminal)
    monkeypatch.setattr(check_command, "PROGRESS_DELAY_S", 0.0)
    monkeypatch.setattr(check_command, "PROGRESS_INTERVAL_S", 0.0)
    args = build_parser().parse_args(["check", str(ROOT / "missions" / "arm_recovery.orc")])
    assert check_command.run(args) == 0
    text = terminal.getvalue()
    assert "states explored" in text and "properties done" in text
    assert text.endswith("\r\033[K")  # erased before the report
    assert "all properties hold" in capsys.readouterr().out


def test_in_a_pipe_nothing_is_shown():
    result = orccad("check", "missions/arm_recovery.orc")
    assert result.returncode == 0 and "explored" not in result.stderr
