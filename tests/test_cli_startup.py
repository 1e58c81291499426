"""Start-up stays lean (issue 14 item 6): building the CLI's parser, ``--version``, ``--help``
and compiling a mission without Robot-Tasks import none of the heavy libraries. The timing
itself is a benchmark (``bench/bench_startup.py``), not a test."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
HEAVY = {"numpy", "mujoco", "pinocchio", "textual", "scipy", "networkx", "pluggy", "mcap"}


def imported(*argv: str) -> set[str]:
    """Top-level names of the modules imported by ``python -X importtime ARGV``."""
    env = {k: v for k, v in os.environ.items() if k != "ORCCAD_DEBUG"}
    result = subprocess.run([sys.executable, "-X", "importtime", *argv], cwd=ROOT, env=env,
                            capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr[-2000:]
    return {line.rsplit("|", 1)[-1].strip().split(".")[0] for line in result.stderr.splitlines()
            if line.startswith("import time:")}


def test_building_the_cli_parser_imports_no_heavy_library():
    names = imported("-c", "import orccad_app.cli; orccad_app.cli.build_parser()")
    assert not names & (HEAVY | {"lark"})


@pytest.mark.parametrize("argv", [["--version"], ["--help"], ["run", "--help"],
                                  ["compile", "missions/abro.orc"],
                                  ["react", "missions/abro.orc", "--inputs", "missions/abro.in"]])
def test_commands_without_robot_tasks_import_no_heavy_library(argv):
    assert not imported("-m", "orccad_app", *argv) & HEAVY
