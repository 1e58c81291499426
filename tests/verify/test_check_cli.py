"""``orccad check`` on the project's missions, and the Promela export."""

from __future__ import annotations

import subprocess
import sys

import pytest

from .conftest import ROOT

MISSIONS = sorted(p.name for p in (ROOT / "missions").glob("*.orc")
                  if p.name not in ("false_property.orc", "paper_rta.orc"))  # no mission


def orccad(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "orccad_app.cli", *args], capture_output=True,
                          text=True, cwd=ROOT)


@pytest.mark.parametrize("name", MISSIONS)
def test_check_proves_the_missions(name):
    result = orccad("check", f"missions/{name}")
    assert result.returncode == 0, result.stdout + result.stderr
    assert "FAIL" not in result.stdout


def test_check_lists_builtins_and_properties():
    result = orccad("check", "missions/arm_recovery.orc")
    for name in ("fatal-aborts", "one-task-per-robot", "no-deadlock", "tasks-end-first",
                 "home_before_tracking", "one_task_at_a_time"):
        assert name in result.stdout


def test_observe_prints_the_quotient():
    result = orccad("check", "missions/abro.orc", "--observe", "O,R")
    assert result.returncode == 0
    assert result.stdout.startswith("observation of ABRO on O, R: 2 classes")


def test_compile_format_promela():
    result = orccad("compile", "missions/abro.orc", "--format", "promela")
    assert result.returncode == 0
    assert "active proctype mission()" in result.stdout and "i_A" in result.stdout


def test_check_writes_promela_with_the_properties(tmp_path):
    out = tmp_path / "abro.pml"
    assert orccad("check", "missions/abro.orc", "--promela", str(out)).returncode == 0
    assert "ltl p_o_needs_a {" in out.read_text()
