"""``orccad react`` and ``orccad compile`` as a user runs them: output, exit status, errors."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def orccad(*args: str, stdin: str | None = None, cwd: Path = ROOT) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "orccad_app.cli", *args], input=stdin,
                          capture_output=True, text=True, cwd=cwd)


def test_react_abro_jsonl_prints_esterels_abro():
    result = orccad("react", "missions/abro.orc", "--inputs", "missions/abro.in", "--jsonl")
    assert result.returncode == 0, result.stderr
    records = [json.loads(line) for line in result.stdout.splitlines()]
    assert [r["instant"] for r in records] == list(range(1, 10))
    assert [r["outputs"] for r in records] == [[], [], ["O"], [], [], ["O"], [], [], ["O"]]
    assert records[2] == {"instant": 3, "inputs": ["B"], "outputs": ["O"], "values": {},
                          "status": "running"}


def test_react_reads_the_script_from_stdin_and_prints_a_table():
    result = orccad("react", "missions/abro.orc", stdin="\nA\nB\n")
    assert result.returncode == 0
    lines = result.stdout.splitlines()
    assert len(lines) == 3 and "-> O" in lines[2] and "[running]" in lines[2]
    assert "-> -" in lines[1]


def test_react_with_times_reports_them(tmp_path):
    (tmp_path / "t.orc").write_text("mission T { output O; await 1 s; emit O; }\n")
    (tmp_path / "t.in").write_text("@0\n@0.5\n@1.25\n")
    result = orccad("react", "t.orc", "--inputs", "t.in", "--jsonl", cwd=tmp_path)
    records = [json.loads(line) for line in result.stdout.splitlines()]
    assert [r["time_s"] for r in records] == [0.0, 0.5, 1.25]
    assert [r["status"] for r in records] == ["running", "running", "done"]


def test_unknown_input_in_the_script_is_located(tmp_path):
    (tmp_path / "bad.in").write_text("A\nA  Q\n")
    result = orccad("react", str(ROOT / "missions/abro.orc"), "--inputs", "bad.in", cwd=tmp_path)
    assert result.returncode == 2
    assert "bad.in:2:4: error: 'Q' is not an input signal" in result.stderr
    assert "Traceback" not in result.stderr


def test_decreasing_time_is_rejected(tmp_path):
    (tmp_path / "t.in").write_text("@2\n@1\n")
    result = orccad("react", str(ROOT / "missions/abro.orc"), "--inputs", "t.in", cwd=tmp_path)
    assert result.returncode == 2 and "backwards" in result.stderr


def test_syntax_error_exit_2_with_caret(tmp_path):
    (tmp_path / "s.orc").write_text("mission M {\n    output O;\n    emit O\n}\n")
    result = orccad("compile", "s.orc", cwd=tmp_path)
    assert result.returncode == 2
    first = result.stderr.splitlines()[0]
    assert first.startswith("s.orc:3:") and "error" in first and "';'" in first
    assert "^" in result.stderr and "Traceback" not in result.stderr


def test_non_causal_program_exit_2_with_location(tmp_path):
    (tmp_path / "c.orc").write_text("mission M {\n  output O;\n  signal S { if S { } else { emit S; } }\n}\n")
    result = orccad("compile", "c.orc", cwd=tmp_path)
    assert result.returncode == 2
    assert result.stderr.startswith("c.orc:3:17: error: non-causal program")


def test_instantaneous_loop_exit_2_with_location(tmp_path):
    (tmp_path / "l.orc").write_text("mission M {\n  output O;\n  loop { emit O; }\n}\n")
    result = orccad("compile", "l.orc", cwd=tmp_path)
    assert result.returncode == 2
    assert result.stderr.startswith("l.orc:3:3: error: instantaneous loop")


def test_missing_file_is_a_clean_error():
    result = orccad("compile", "no/such.orc")
    assert result.returncode == 2 and "no such file" in result.stderr


def test_compile_formats():
    summary = orccad("compile", "missions/abro.orc")
    assert summary.returncode == 0 and "states: 5" in summary.stdout
    as_json = json.loads(orccad("compile", "missions/abro.orc", "--format", "json").stdout)
    assert as_json["state_count"] == 5 and as_json["transition_count"] == 14
    assert [s["name"] for s in as_json["inputs"]] == ["A", "B", "R"]
    dot = orccad("compile", "missions/abro.orc", "--format", "dot").stdout
    assert dot.startswith('digraph "ABRO"') and dot.count("->") >= 14


def test_compile_writes_to_a_file(tmp_path):
    out = tmp_path / "abro.dot"
    result = orccad("compile", "missions/abro.orc", "--format", "dot", "-o", str(out))
    assert result.returncode == 0 and out.read_text().startswith("digraph")


def test_unknown_mission_is_named():
    result = orccad("compile", "missions/abro.orc", "--mission", "Nope")
    assert result.returncode == 2 and "no mission named 'Nope'" in result.stderr
