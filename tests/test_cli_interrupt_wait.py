"""Ctrl-C or SIGTERM while ``orccad run --foxglove`` waits for a subscriber (issue 28, 8):
the run ends before it starts, with its report, exit 130 and a valid (not 0-byte) trace."""

from __future__ import annotations

import json
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import pytest
from mcap.reader import make_reader

ROOT = Path(__file__).resolve().parents[1]


def _free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


@pytest.mark.parametrize("sent, reason", [(signal.SIGINT, "interrupted (Ctrl-C)"),
                                           (signal.SIGTERM, "interrupted (SIGTERM)")])
def test_an_interrupt_while_waiting_for_foxglove_keeps_the_report_and_the_trace(
        tmp_path, sent, reason):
    pytest.importorskip("foxglove", reason="the foxglove extra is not installed")
    trace = tmp_path / "run.mcap"
    process = subprocess.Popen(
        [sys.executable, "-m", "orccad_app.cli", "run", "missions/arm_pid.orc", "--json",
         "--trace", str(trace), "--foxglove", "--foxglove-port", str(_free_port()),
         "--foxglove-wait", "60"],
        cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert process.stderr is not None
        line = process.stderr.readline()  # the URL: the server is up and the wait begins
        assert "streaming to Foxglove" in line, line
        time.sleep(0.3)
        started = time.monotonic()
        process.send_signal(sent)
        out, err = process.communicate(timeout=30)
        assert time.monotonic() - started < 10  # not at the end of the 60 s wait
    finally:
        process.kill()
    assert process.returncode == 130, err
    report = json.loads(out)
    assert report["status"] == "aborted" and report["reason"] == reason
    assert report["sim_time_s"] == 0.0
    with trace.open("rb") as stream:
        summary = make_reader(stream).get_summary()
    assert summary is not None and summary.channels
