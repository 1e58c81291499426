"""A Module-Task period set whose gcd is far finer than its periods is refused at once
(issue 12: `period 1000001 ns` beside `period 1 ms` made `orccad run` crawl)."""

from __future__ import annotations

import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def _orccad(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "orccad_app", *args], capture_output=True,
                          text=True, cwd=ROOT, timeout=120)


def test_incommensurate_periods_fail_fast_with_the_periods_named(tmp_path):
    source = (ROOT / "missions/arm_pid.orc").read_text(encoding="utf-8")
    assert "period 1 ms" in source
    mission = tmp_path / "gcd.orc"
    mission.write_text(source.replace("period 1 ms", "period 1000001 ns"), encoding="utf-8")
    start = time.monotonic()
    result = _orccad("run", str(mission), "--until", "0.05")
    assert time.monotonic() - start < 60  # it used to run for minutes
    assert result.returncode == 2, result.stderr
    assert "greatest common divisor of 1 ns" in result.stderr
    assert "1000001 ns" in result.stderr and "Traceback" not in result.stderr


def test_commensurate_periods_still_run():
    result = _orccad("run", "missions/arm_pid.orc", "--until", "0.05")
    assert result.returncode in (0, 1), result.stderr
    assert "greatest common divisor" not in result.stderr
