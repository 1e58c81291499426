"""Traces: CSV and MCAP files written as the run goes, valid after failures and Ctrl-C,
bit-for-bit reproducible from the seed."""

from __future__ import annotations

import csv
import json
from pathlib import Path

import pytest
from mcap.reader import make_reader

from orccad_app.diagnostics import OrccadError
from orccad_app.executive import Observer
from orccad_app.mission.plan import plan_mission
from orccad_app.mission.injection import Injection
from orccad_app.mission.run import MissionRun
from orccad_app.pipeline import load, select_mission
from orccad_app.trace import TraceRecorder, open_trace

ROOT = Path(__file__).resolve().parents[2]


def _plan(replacements=None, tmp_path=None):
    path = ROOT / "missions" / "arm_pid.orc"
    if replacements:
        text = path.read_text()
        for old, new in replacements.items():
            text = text.replace(old, new)
        path = tmp_path / "edited.orc"
        path.write_text(text)
    source = load(path)
    return plan_mission(source, select_mission(source, None))


def _traced(path, plan=None, **options):
    writer = open_trace(path, {"mission": "ArmPID"})
    try:
        run = MissionRun(plan or _plan(), **options)
        run.add_observer(TraceRecorder(writer))
        return run.run()
    finally:
        writer.close()


def _mcap_messages(path):
    with open(path, "rb") as stream:
        reader = make_reader(stream)
        return [(channel.topic, message.log_time, json.loads(message.data))
                for _, channel, message in reader.iter_messages()]


def test_csv_trace_holds_jobs_values_and_reactions(tmp_path):
    path = tmp_path / "run.csv"
    result = _traced(path, until_ns=20_000_000)
    rows = list(csv.DictReader(path.open()))
    assert result.status == "timeout"
    assert list(rows[0]) == ["time_ns", "event", "module", "port", "job", "value"]
    events = {row["event"] for row in rows}
    assert {"reaction", "task_start", "activate", "release", "start", "finish", "read",
            "write"} <= events
    first_tau = next(r for r in rows if r["event"] == "write" and r["port"] == "tau")
    assert (first_tau["module"], first_tau["time_ns"]) == ("TrackPID.ctrl", "1300000")
    assert len(json.loads(first_tau["value"])) == 3


def test_mcap_trace_reads_back_with_the_mcap_reader(tmp_path):
    path = tmp_path / "run.mcap"
    _traced(path, injections=[Injection("TrackPID.TrackingLost", 50_000_000)])
    messages = _mcap_messages(path)
    topics = {topic for topic, _, _ in messages}
    assert {"/orccad/release", "/ports/TrackPID/ctrl/tau", "/orccad/reaction",
            "/orccad/exception", "/orccad/task_end", "/log"} <= topics
    end = [m for topic, _, m in messages if topic == "/orccad/task_end"]
    assert end == [{"task": "TrackPID", "site": 0, "outcome": "TrackingLost"}]
    times = [t for _, t, _ in messages]
    assert times == sorted(times) and times[-1] == 50_000_000
    with open(path, "rb") as stream:
        metadata = list(make_reader(stream).iter_metadata())
    assert metadata[0].name == "orccad" and metadata[0].metadata["mission"] == "ArmPID"


class _CtrlC(Observer):
    """Raises KeyboardInterrupt at the first release after ``t_ns``."""

    def __init__(self, t_ns):
        self.t_ns = t_ns

    def on_release(self, t_ns, module, job):
        if t_ns >= self.t_ns:
            raise KeyboardInterrupt


def test_an_interrupted_run_leaves_a_valid_trace(tmp_path):
    path = tmp_path / "run.mcap"
    result = _traced(path, observers=[_CtrlC(30_000_000)])
    assert (result.status, result.interrupted) == ("aborted", True)
    messages = _mcap_messages(path)
    assert messages and 29_000_000 <= messages[-1][1] <= 30_000_000


def test_a_failed_run_leaves_a_valid_trace(tmp_path):
    deadlock = {"connect traj.qd     -> ctrl.qd     : asyn/asyn;":
                "connect traj.qd     -> ctrl.qd     : syn/syn;",
                "connect arm.q       -> jl.q        : asyn/asyn;":
                "connect arm.q       -> jl.q        : asyn/asyn;\n"
                "    connect ctrl.tau -> traj.q : syn/syn;"}
    path = tmp_path / "run.csv"
    result = _traced(path, plan=_plan(deadlock, tmp_path))
    assert result.status == "failed" and "deadlock" in result.reason
    rows = list(csv.DictReader(path.open()))
    assert rows[-1]["event"] == "deadlock"


def test_same_seed_same_trace_bit_for_bit(tmp_path):
    jitter = {"wcet 0.3 ms on cpu0 priority 1": "wcet 0.3 ms bcet 0.05 ms on cpu0 priority 1"}
    files = []
    for name, seed in (("a", 7), ("b", 7), ("c", 8)):
        for suffix in (".csv", ".mcap"):
            path = tmp_path / f"{name}{suffix}"
            _traced(path, plan=_plan(jitter, tmp_path), seed=seed, until_ns=100_000_000)
            files.append(path.read_bytes())
    a_csv, a_mcap, b_csv, b_mcap, c_csv, c_mcap = files
    assert a_csv == b_csv and a_mcap == b_mcap
    assert a_csv != c_csv  # the seed draws the execution times


def test_unknown_trace_format_is_bad_input(tmp_path):
    with pytest.raises(OrccadError, match="unknown trace format '.txt'"):
        open_trace(tmp_path / "run.txt")
