"""Campaigns of many runs: every run committed before the campaign goes on, each run's
objects freed in its worker (flat memory; bench/bench_campaign_scale.py measures it)."""

from __future__ import annotations

import sqlite3
import subprocess
import sys
import textwrap

from orccad_app.campaign.adapter import PropertyResult, RunRecord
from orccad_app.campaign.executor import PoolBackend
from orccad_app.campaign.runner import Campaign, CampaignOptions
from orccad_app.campaign.setting import RunSetting
from orccad_app.campaign.spec import parse_spec
from orccad_app.campaign.store import CampaignStore

from .conftest import ROOT

ARM = str(ROOT / "missions" / "arm_pid.orc")
SHORT = """\
mission = "ArmPID"
seed = 3
until_s = 0.02
[timing]
"TrackPID.ctrl.wcet_ms" = "U(0.1, 0.9)"
"""


def _complete_runs(db: str) -> set[int]:
    """Runs whose row and drawn parameters are both visible to another connection."""
    with sqlite3.connect(db) as other:
        runs = {row[0] for row in other.execute("SELECT run FROM runs")}
        params = {row[0] for row in other.execute("SELECT run FROM params")}
    return runs & params


def test_every_run_is_committed_before_the_campaign_goes_on(tmp_path):
    """Runs are written in batches (those that come back together), each batch committed
    before the progress callback: a campaign killed at any point has every run it reported."""
    db = str(tmp_path / "c.db")
    seen = []

    def progress(done, limit, prefix):
        committed = _complete_runs(db)
        assert len(committed) >= done, (committed, done)
        seen.append(done)

    result = Campaign(ARM, parse_spec(SHORT), CampaignOptions(runs=8, db=db)).run(
        progress, PoolBackend(2))
    assert seen and seen[-1] == 8 and len(result.records) == 8
    assert _complete_runs(db) == set(range(8))


def test_a_batch_is_one_transaction_with_every_table(tmp_path):
    store = CampaignStore(tmp_path / "b.db")
    records = [RunRecord(RunSetting(i, 100 + i, 1.0, values={"x": float(i)}), "done", None,
                         "done", 1.0, 0.1, {"m": 2.0 * i}, {"p": PropertyResult(True, 0.5)})
               for i in range(3)]
    store.add_many([(r, f"orccad run #{r.index}") for r in records])
    assert [(r.index, r.metrics, r.properties) for r in store.records()] == \
        [(r.index, r.metrics, r.properties) for r in records]
    assert [store.replay(i) for i in range(3)] == [f"orccad run #{i}" for i in range(3)]
    assert store.db.execute("PRAGMA synchronous").fetchone()[0] == 1  # NORMAL under WAL


def test_a_worker_frees_each_run():
    """After each run a worker has no object of it left (the executive's reference cycles
    hold MuJoCo's models and data, C memory the automatic collector does not see)."""
    script = textwrap.dedent(f"""
        import weakref
        from orccad_app.campaign import adapter, executor
        from orccad_app.campaign.setting import draw_setting
        from orccad_app.campaign.spec import parse_spec

        built = []
        make = adapter.CompiledMission.session
        def tracked(self, *args, **kwargs):
            session = make(self, *args, **kwargs)
            built.append(weakref.ref(session.run))
            return session
        adapter.CompiledMission.session = tracked
        spec = parse_spec({SHORT!r})
        compiled = adapter.CompiledMission({ARM!r})
        for index in range(3):
            job = executor.Job({ARM!r}, compiled.name, compiled.digest,
                               draw_setting(spec, index, 0.02))
            assert executor.run_job(job).status == "timeout"  # cut at 20 ms
            assert all(ref() is None for ref in built), index
        print("freed", len(built))
    """)
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                          timeout=300, cwd=ROOT)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "freed 3"


def test_the_parent_keeps_no_finished_run_in_memory(tmp_path):
    """The campaign folds each run into counts and keeps it on disk only: while 60 runs
    (finished out of order) go by, at most the few waiting for an earlier run are alive in
    the parent; the statistics, read back from the database, are those of every run."""
    import weakref

    from tests.campaign.conftest import AUV, LEAK_SPEC
    from tests.campaign.test_sequential_order import ScriptedBackend

    returned: list[weakref.ref] = []

    class Tracked(ScriptedBackend):
        def result(self, future, job):
            record = super().result(future, job)
            returned.append(weakref.ref(record))
            return record

    order = [{i ^ 1} for i in range(60)]  # 1, 0, 3, 2, …: each pair out of order
    alive = []

    def progress(done, limit, prefix):  # no gc.collect(): a record must not even wait for
        alive.append(sum(ref() is not None for ref in returned))  # the cycle collector

    spec = parse_spec(LEAK_SPEC, "leak.campaign.toml")
    campaign = Campaign(AUV, spec, CampaignOptions(runs=60, db=str(tmp_path / "m.db")))
    result = campaign.run(progress, Tracked(order, lambda i: "aborted" if i % 5 == 0
                                              else "done", workers=2))
    assert len(returned) == 60 and max(alive) <= 4, alive
    assert [r.index for r in result.records] == list(range(60))
    assert result.estimates["done"]["count"] == 48
