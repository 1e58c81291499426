"""No process left behind, nothing lost, when a campaign is killed (issue 28, 8).

``orccad campaign`` is started for real (a pool of two workers), then killed: after ``SIGKILL``
its workers must die with it; after ``SIGTERM`` it ends like ``orccad run`` does (exit 130, a
message, the finished runs reported and kept in the database), its workers gone.
"""

from __future__ import annotations

import json
import os
import signal
import sqlite3
import subprocess
import sys
import time
from pathlib import Path

import pytest

from tests.campaign.conftest import AUV, LEAK_SPEC, ROOT

pytestmark = pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")


def _children(pid: int) -> set[int]:
    """The processes whose parent is ``pid`` (zombies excluded)."""
    found = set()
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            stat = (entry / "stat").read_text()
        except OSError:
            continue
        fields = stat[stat.rindex(")") + 2:].split()
        if int(fields[1]) == pid and fields[0] != "Z":
            found.add(int(entry.name))
    return found


def _alive(pid: int) -> bool:
    try:
        stat = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return False
    return stat[stat.rindex(")") + 2:].split()[0] != "Z"


def _start(tmp_path: Path, *extra: str) -> tuple[subprocess.Popen, set[int]]:
    spec = tmp_path / "leak.campaign.toml"
    spec.write_text(LEAK_SPEC, encoding="utf-8")
    process = subprocess.Popen(
        [sys.executable, "-m", "orccad_app.cli", "campaign", AUV, "--spec", str(spec),
         "--runs", "40", "--workers", "2", "--db", str(tmp_path / "c.db"), *extra],
        cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 120
    workers: set[int] = set()
    while len(workers) < 2 and time.monotonic() < deadline and process.poll() is None:
        time.sleep(0.1)
        workers = _children(process.pid)
    assert len(workers) >= 2, "the campaign's workers never started"
    return process, workers


def _gone(pids: set[int], within_s: float = 15.0) -> set[int]:
    deadline = time.monotonic() + within_s
    while time.monotonic() < deadline and any(_alive(p) for p in pids):
        time.sleep(0.1)
    return {p for p in pids if _alive(p)}


def _reap(process: subprocess.Popen, workers: set[int]) -> None:
    """Whatever the test found, leave no process of it behind."""
    for pid in [process.pid, *workers]:
        if _alive(pid):
            os.kill(pid, signal.SIGKILL)
    process.wait(timeout=30)


def test_sigkill_of_a_campaign_leaves_no_worker_behind(tmp_path):
    process, workers = _start(tmp_path)
    try:
        process.kill()
        process.wait(timeout=30)
        left = _gone(workers)
        assert not left, f"workers left behind after SIGKILL: {sorted(left)}"
    finally:
        _reap(process, workers)


def test_sigterm_ends_a_campaign_like_ctrl_c(tmp_path):
    db = tmp_path / "c.db"
    process, workers = _start(tmp_path, "--json")
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline:  # at least one run finished and recorded
        time.sleep(0.2)
        try:
            with sqlite3.connect(db) as connection:
                if connection.execute("select count(*) from runs").fetchone()[0]:
                    break
        except sqlite3.Error:
            continue
    process.send_signal(signal.SIGTERM)
    try:
        out, err = process.communicate(timeout=60)
    finally:
        _reap(process, workers)
    assert process.returncode == 130, err
    assert "terminated (SIGTERM); continue with --resume" in err
    result = json.loads(out)
    assert result["interrupted"] is True and result["runs"] >= 1
    with sqlite3.connect(db) as connection:
        assert connection.execute("select count(*) from runs").fetchone()[0] >= result["runs"]
    assert not _gone(workers), "workers left behind after SIGTERM"
