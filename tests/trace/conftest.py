"""One MCAP trace of ``missions/arm_recovery.orc`` shared by the trace tests (a run costs
seconds: it is made once per session)."""

from __future__ import annotations

import json
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

import pytest


@dataclass(frozen=True)
class RecoveryRun:
    """The trace file and the ``--json`` report of ``orccad run missions/arm_recovery.orc
    --inject Stop@3 --until 4`` (a timeout at 4 s, during the park)."""

    path: Path
    report: dict


@pytest.fixture(scope="session")
def recovery_run(tmp_path_factory) -> RecoveryRun:
    path = tmp_path_factory.mktemp("recovery") / "recovery.mcap"
    result = subprocess.run([sys.executable, "-m", "orccad_app.cli", "run",
                             "missions/arm_recovery.orc", "--inject", "Stop@3", "--until", "4",
                             "--trace", str(path), "--json"], capture_output=True, text=True)
    assert result.returncode == 1, result.stderr  # timeout at 4 s, during the park
    return RecoveryRun(path, json.loads(result.stdout))
