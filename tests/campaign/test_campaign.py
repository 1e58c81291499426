"""Campaigns end to end on short AUV runs: known probabilities, replay, resume, crashes."""

from __future__ import annotations

import json
import os
import signal
import sqlite3

import pytest

from orccad_app.campaign import executor
from orccad_app.campaign.adapter import CompiledMission
from orccad_app.campaign.executor import PoolBackend
from orccad_app.campaign.runner import Campaign, CampaignOptions
from orccad_app.campaign.spec import load_spec
from orccad_app.trace import report_dict

from .conftest import AUV, orccad


def _campaign(spec_path, db, runs, **options) -> Campaign:
    return Campaign(AUV, load_spec(spec_path), CampaignOptions(runs=runs, db=str(db), **options))


def _rows(db) -> list[tuple]:
    with sqlite3.connect(db) as connection:
        return connection.execute(
            "SELECT run, seed, status, outcome, sim_time_s, setting FROM runs ORDER BY run"
        ).fetchall()


@pytest.mark.slow
def test_a_leak_with_probability_0_3_gives_p_aborted_near_0_3(leak_spec, tmp_path):
    """Known by construction: every leak during the dive aborts the mission, nothing else
    does, so P(aborted) is the leak's occurrence probability 0.3."""
    result = orccad("campaign", AUV, "--spec", str(leak_spec), "--runs", "60", "--workers", "2",
                    "--db", str(tmp_path / "leak.db"), "--json")
    assert result.returncode == 0, result.stderr
    data = json.loads(result.stdout)
    aborted = data["estimates"]["aborted"]
    leaks = sum(1 for r in data["results"] if r["setting"]["injections"])
    assert aborted["count"] == leaks == data["estimates"]["aborted(Leak)"]["count"]
    assert aborted["low"] <= 0.3 <= aborted["high"]
    assert aborted["runs"] == 60 and data["estimates"]["timeout"]["count"] == 60 - leaks
    assert data["distributions"]["robustness"]["shallow"]["n"] == 60
    with sqlite3.connect(tmp_path / "leak.db") as db:  # the documented schema, by SQL
        count, = db.execute("SELECT COUNT(*) FROM runs WHERE outcome = 'aborted(Leak)'").fetchone()
        deepest, = db.execute("SELECT MAX(value) FROM metrics WHERE name = 'max(auv.depth)'"
                              ).fetchone()
    assert count == leaks and 0 < deepest < 30


def test_the_replay_command_reproduces_the_run_bit_for_bit(leak_spec, tmp_path):
    campaign = _campaign(leak_spec, tmp_path / "r.db", 4)
    result = campaign.run(backend=PoolBackend(1))
    record = next(r for r in result.records if r.setting.injections)
    command = campaign.replay(record.setting)
    assert command.startswith(f"orccad run {AUV} --mission AuvSurvey --seed ")
    assert "--inject auv.leak=1@" in command and "--timing Dive.pilot.wcet_ms=" in command
    replayed = orccad(*command.split()[1:], "--json")
    report = json.loads(replayed.stdout)
    # the same run in this process, through the campaign's adapter
    compiled = CompiledMission(AUV)
    here = compiled.session(record.setting).execute().as_dict()
    for data in (report, here):
        data.pop("wall_time_s")
    assert {p["name"] for p in report["properties"]} >= {"leak_surfaces", "safe_depth"}
    assert report == here
    for verdict in report["properties"]:  # the campaign's row holds the same verdicts
        found = record.properties[verdict["name"]]
        assert found.robustness == verdict["robustness"]
        assert found.holds == {"true": True, "false": False}.get(verdict["verdict"])
    assert (report["status"], report["reason"]) == (record.status, record.reason)
    assert report["sim_time_s"] == record.sim_time_s


def test_observing_signal_extrema_does_not_change_the_run(leak_spec):
    from orccad_app.campaign.adapter import execute
    from orccad_app.campaign.setting import draw_setting

    compiled = CompiledMission(AUV)
    setting = draw_setting(load_spec(leak_spec), 2, 30.0)
    plain = report_dict(compiled.session(setting).execute().result)
    watched = execute(compiled, setting, ("auv.depth", "auv.attitude[1]"))
    assert watched.sim_time_s == plain["sim_time_s"] and watched.status == plain["status"]
    assert watched.metrics["max(auv.depth)"] > 1.0


@pytest.mark.slow
def test_an_interrupted_campaign_resumes_without_losing_a_run(leak_spec, tmp_path):
    reference = _campaign(leak_spec, tmp_path / "ref.db", 6).run(backend=PoolBackend(2))
    assert len(reference.records) == 6

    def stop_after_two(done, limit, prefix):
        if done >= 2:
            raise KeyboardInterrupt

    first = _campaign(leak_spec, tmp_path / "cut.db", 6).run(stop_after_two, PoolBackend(2))
    assert first.interrupted and 2 <= len(_rows(tmp_path / "cut.db")) < 6
    again = orccad("campaign", AUV, "--spec", str(leak_spec), "--runs", "6", "--workers", "1",
                   "--db", str(tmp_path / "cut.db"), "--json")
    assert again.returncode == 2 and "--resume" in again.stderr  # never overwritten
    resumed = _campaign(leak_spec, tmp_path / "cut.db", 6, resume=True).run(
        backend=PoolBackend(2))
    assert not resumed.interrupted
    assert _rows(tmp_path / "cut.db") == _rows(tmp_path / "ref.db")


@pytest.mark.slow
def test_a_killed_worker_loses_no_run(leak_spec, tmp_path):
    backend = PoolBackend(2)
    killed = []

    def kill_one(done, limit, prefix):
        if not killed:
            pid = backend.worker_pids()[0]
            os.kill(pid, signal.SIGKILL)
            killed.append(pid)

    result = _campaign(leak_spec, tmp_path / "k.db", 6).run(kill_one, backend)
    rows = _rows(tmp_path / "k.db")
    assert killed and [row[0] for row in rows] == list(range(6))
    assert all(row[2] != "crashed" for row in rows)
    assert any(r.attempts == 2 for r in result.records)  # retried after the pool broke
    _campaign(leak_spec, tmp_path / "ref.db", 6).run(backend=PoolBackend(1))
    assert rows == _rows(tmp_path / "ref.db")


def test_a_crashing_run_is_retried_once_then_recorded(leak_spec, tmp_path, monkeypatch):
    flag = tmp_path / "crashed-once"

    real = executor.execute

    def flaky(compiled, setting, *args, **kwargs):
        if setting.index == 1 and not flag.exists():
            flag.write_text("x")
            raise RuntimeError("boom")
        if setting.index == 2:
            raise RuntimeError("always")
        return real(compiled, setting, *args, **kwargs)

    monkeypatch.setattr(executor, "execute", flaky)  # forked workers inherit it
    result = _campaign(leak_spec, tmp_path / "c.db", 3).run(backend=PoolBackend(1))
    by_index = {r.index: r for r in result.records}
    assert by_index[1].status != "crashed" and by_index[1].attempts == 2
    assert by_index[2].status == "crashed" and "always" in by_index[2].error
    assert by_index[0].attempts == 1


@pytest.mark.slow
def test_dask_local_cluster_gives_the_same_rows_as_the_pool(leak_spec, tmp_path):
    distributed = pytest.importorskip("distributed")
    from orccad_app.campaign.executor import DaskBackend

    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, host="127.0.0.1",
                                  dashboard_address=None, processes=True) as cluster, \
            distributed.Client(cluster) as client:
        assert cluster.scheduler_address.startswith("tcp://127.0.0.1:")
        result = _campaign(leak_spec, tmp_path / "d.db", 4).run(backend=DaskBackend(client))
        command = orccad("campaign", AUV, "--spec", str(leak_spec), "--runs", "4",
                         "--cluster", cluster.scheduler_address, "--db",
                         str(tmp_path / "cli.db"), "--json")
    assert result.backend == "dask"
    assert command.returncode == 0, command.stderr
    assert json.loads(command.stdout)["backend"] == "dask"
    _campaign(leak_spec, tmp_path / "p.db", 4).run(backend=PoolBackend(2))
    assert _rows(tmp_path / "d.db") == _rows(tmp_path / "p.db") == _rows(tmp_path / "cli.db")


@pytest.mark.slow
def test_sequential_stopping_and_hypothesis_test_stop_early(leak_spec, tmp_path):
    result = orccad("campaign", AUV, "--spec", str(leak_spec), "--workers", "2",
                    "--hypothesis", "P(aborted) <= 0.9", "--delta", "0.05", "--runs", "40",
                    "--db", str(tmp_path / "h.db"), "--json")
    assert result.returncode == 0, result.stderr
    data = json.loads(result.stdout)
    assert data["stopped_by"] == "hypothesis" and data["hypothesis"]["decision"] == "accepted"
    assert data["runs"] < 40


@pytest.mark.slow
def test_the_report_and_the_summary(leak_spec, tmp_path):
    html = tmp_path / "report.html"
    result = orccad("campaign", AUV, "--spec", str(leak_spec), "--runs", "4", "--workers", "1",
                    "--db", str(tmp_path / "s.db"), "--report", str(html))
    assert result.returncode == 0, result.stderr
    assert "Clopper-Pearson" in result.stdout and "robustness shallow" in result.stdout
    text = html.read_text()
    assert text.count("data:image/png;base64,") >= 3 and "orccad run" in text
    folder = tmp_path / "report"
    again = orccad("campaign", AUV, "--spec", str(leak_spec), "--runs", "4", "--workers", "1",
                   "--db", str(tmp_path / "s.db"), "--resume", "--report", str(folder))
    assert again.returncode == 0, again.stderr
    assert (folder / "outcomes.png").is_file() and "![outcomes]" in (folder / "report.md"
                                                                     ).read_text()
