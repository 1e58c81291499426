"""``PREFIX_main`` refuses a script that is not a regular file as ``orccad react`` does (issue
34, item 4): a FIFO would block it until a writer came, a folder reads as an empty script (it
ran nothing and exited 0), a device may never end. Same message, exit status 2."""

from __future__ import annotations

import os
import subprocess

import pytest

from orccad_app.cli import main as orccad
from tests.codegen.cbuild import STRICT, build
from tests.codegen.conftest import MISSIONS, generated


def _react_error(script: str, capsys) -> str:
    assert orccad(["react", str(MISSIONS / "abro.orc"), "--composed", "--inputs", script,
                   "--jsonl"]) == 2
    return capsys.readouterr().err


@pytest.mark.parametrize("kind", ["fifo", "folder", "device", "missing"])
def test_a_script_that_is_not_a_regular_file_is_refused_as_react_does(kind, tmp_path, capsys):
    binary = build(generated("abro", "ABRO").program)
    script = {"fifo": tmp_path / "s.in", "folder": tmp_path / "d.in",
              "device": "/dev/zero", "missing": tmp_path / "none.in"}[kind]
    if kind == "fifo":
        os.mkfifo(script)
    elif kind == "folder":
        os.mkdir(script)
    for argv in ([str(binary), str(script)], [str(binary), str(script), "--trace"]):
        done = subprocess.run(argv, capture_output=True, text=True, timeout=20)
        assert done.returncode == 2 and done.stdout == ""
        assert done.stderr == _react_error(str(script), capsys)
    assert "regular file" in done.stderr or "folder" in done.stderr or "no such" in done.stderr


def test_the_program_builds_when_the_caller_picks_the_posix_level(tmp_path):
    """``-D_POSIX_C_SOURCE=…`` on the command line is not redefined (a warning, an error
    with -Werror)."""
    binary = build(generated("abro", "ABRO").program,
                   STRICT + ("-O0", "-D_POSIX_C_SOURCE=200809L"))
    script = tmp_path / "s.in"
    script.write_text("\nA B\n")
    done = subprocess.run([str(binary), str(script)], capture_output=True, text=True,
                          timeout=20)
    assert done.returncode == 0 and '"outputs": ["O"]' in done.stdout
