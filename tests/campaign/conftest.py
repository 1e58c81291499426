"""Shared pieces of the campaign tests: short AUV campaigns (30-40 s horizons, a few runs)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
AUV = str(ROOT / "missions" / "auv_survey.orc")

LEAK_SPEC = """\
mission = "AuvSurvey"
seed = 5
until_s = 30
signals = ["auv.depth"]

[params]
"auv.cb_height_m" = "U(0.03, 0.07)"

[timing]
"Dive.pilot.wcet_ms" = "U(0.5, 3)"

[[inject]]
event = "auv.leak=1@U(8, 12)"      # during the dive: the Leak observer aborts the mission
probability = 0.3

[[check]]
name = "shallow"
metric = "max(auv.depth)"
below = 30.0
"""


def orccad(*args: str, cwd: Path = ROOT) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "orccad_app.cli", *args],
                          capture_output=True, text=True, cwd=cwd, timeout=600)


@pytest.fixture
def leak_spec(tmp_path: Path) -> Path:
    path = tmp_path / "leak.campaign.toml"
    path.write_text(LEAK_SPEC, encoding="utf-8")
    return path
