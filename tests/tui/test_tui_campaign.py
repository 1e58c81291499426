"""The campaign screen (issue 26): a campaign started from a spec in its own process, its
estimates, histograms and closest runs read from the database as runs finish, a run replayed
in the live view with its setting; stopping leaves the database resumable; a falsification
the same way."""

from __future__ import annotations

import contextlib
import os
import sqlite3
import subprocess
import sys

import pytest

from orccad_app.campaign.runner import Campaign, CampaignOptions
from orccad_app.campaign.spec import load_spec
from orccad_app.campaign.stats import clopper_pearson
from orccad_app.campaign.store import CampaignStore
from orccad_app.tui.app import OrccadApp
from orccad_app.diagnostics import OrccadError
from orccad_app.tui.campaigns import Bin, histogram, read_campaign, read_study
from orccad_app.tui.screens.campaign import CampaignScreen, histogram_text
from orccad_app.tui.screens.run import RunScreen

from tests.tui.test_tui_app import _text, _until, pilot_test

MISSION = "missions/arm_pid.orc"
SPEC = "missions/arm_pid.campaign.toml"
SIZE = (160, 48)
WAIT_S = 120.0
"""A campaign's process on a loaded machine: start-up, compilation, a few runs."""


@pytest.fixture
def short_spec(tmp_path) -> str:
    """The arm's campaign spec with runs cut at 0.5 s (status ``timeout``): quick runs."""
    path = tmp_path / "arm_short.campaign.toml"
    text = open(SPEC, encoding="utf-8").read().replace("seed = 1", "seed = 1\nuntil_s = 0.5")
    path.write_text(text, encoding="utf-8")
    return str(path)


def test_histogram_bins_cover_the_range_and_count_every_value():
    bins = histogram([-1.0, 0.0, 0.5, 1.0, 3.0], bins=4)
    assert [(b.low, b.high) for b in bins] == [(-1.0, 0.0), (0.0, 1.0), (1.0, 2.0), (2.0, 3.0)]
    assert [b.count for b in bins] == [1, 2, 1, 1]  # [low, high); the last holds 3.0
    assert histogram([2.0, 2.0]) == [Bin(2.0, 2.0, 2)]
    assert histogram([float("nan"), float("inf")]) == [] == histogram([])
    text = histogram_text({"p": [Bin(-1.0, 0.0, 2), Bin(0.0, 1.0, 1)]})
    assert "[red]" in text and "[green]" in text and "(3 runs; left of 0: violated)" in text


def _campaign(app) -> CampaignScreen:
    screen = app.screen
    assert isinstance(screen, CampaignScreen)
    return screen


def _run_screen(app) -> RunScreen:
    """The live run (its report may already cover it: the short runs end in 0.5 s)."""
    return next(s for s in app.screen_stack if isinstance(s, RunScreen))


async def _type(pilot, screen, field: str, text: str) -> None:
    screen.query_one(f"#campaign-{field}").value = text
    await pilot.pause()


@pilot_test
async def test_a_campaign_shows_its_answer_as_runs_finish_replays_a_run_and_stops_resumable(
        tmp_path, short_spec):
    db = str(tmp_path / "arm.db")
    app = OrccadApp([MISSION], selected=MISSION, campaign={"db": db, "workers": 1})
    async with app.run_test(size=SIZE) as pilot:
        await _until(pilot, lambda: isinstance(app.screen, CampaignScreen))
        screen = _campaign(app)
        assert screen.query_one("#campaign-spec").value == SPEC  # the spec beside the file
        await _type(pilot, screen, "spec", short_spec)
        await _type(pilot, screen, "count", "1000")  # more than the test waits for
        await pilot.press("s")
        process = screen.process
        assert screen.state == "running" and process.running
        assert process.args[:2] == ["campaign", MISSION]
        await _until(pilot, lambda: screen.snapshot is not None and screen.snapshot.runs >= 2,
                     timeout=WAIT_S)
        n = screen.snapshot.runs
        status = _text(screen, "#campaign-status")
        assert f"(running): {n}/1000 runs" in status and "P(done) = 0.000" in status
        table = screen.query_one("#estimates")
        rows = {table.get_row_at(i)[0]: table.get_row_at(i) for i in range(table.row_count)}
        assert rows["timeout"][1:3] == [f"{n}/{n}", "1.000"]  # cut at 0.5 s
        k = screen.snapshot.estimates["bounded"]["count"]  # a slow control law may miss it
        low, high = clopper_pearson(k, n, 0.95)
        assert rows["bounded"][1] == f"{k}/{n}"
        assert rows["bounded"][3] == f"[{low:.3f}, {high:.3f}] 95 %"
        assert "bounded" in _text(screen, "#campaign-histogram")
        records = {r.index: r for r in CampaignStore(db).records()}
        first = screen.candidates[0]
        assert first.setting == records[first.run].setting
        assert screen.query_one("#candidates").row_count == len(screen.candidates) > 0
        await pilot.press("enter")  # replay it in the live view while the campaign goes on
        await _until(pilot, lambda: any(isinstance(s, RunScreen) for s in app.screen_stack))
        run = _run_screen(app)
        # the campaign goes on, so the list may have been refreshed between reading `first` and
        # the key: the replayed run is one of the database's runs, with that run's setting
        replayed = run.session.setting
        assert replayed is not None
        records = {r.index: r for r in CampaignStore(db).records()}
        assert replayed == records[replayed.index].setting
        # ... and the run was one of the listed candidates, before the key or after it
        assert replayed.index in {first.run} | {c.run for c in screen.candidates}
        assert run.session.seed == replayed.seed
        assert run.session.run.until_ns == round(replayed.until_s * 1e9)
        periods = {m.name: m.period_ns for m in run.session.run.plan.tcs.module_tasks}
        wanted = dict(t.split("=") for t in replayed.timings)["TrackPID.ctrl.period_ms"]
        assert periods["TrackPID.ctrl"] == round(float(wanted) * 1e6)  # its --timing
        await _until(pilot, lambda: run.finished)  # 0.5 s at 1×
        while app.screen is not screen:
            await pilot.press("escape")
        assert process.running
        await pilot.press("escape")  # closing the screen stops the campaign
        assert not isinstance(app.screen, CampaignScreen)
        assert process.returncode == 130  # interrupted as by Ctrl-C
    with pytest.raises(ProcessLookupError):
        os.killpg(process.process.pid, 0)  # no worker of its pool left behind
    recorded = CampaignStore(db).count()
    assert n <= recorded < 1000
    campaign = Campaign(MISSION, load_spec(short_spec),
                        CampaignOptions(runs=1000, db=db, resume=True))
    assert len(campaign.store.records()) == recorded  # --resume accepts it and keeps them


@pilot_test
async def test_a_falsification_shows_its_trials_and_replays_the_worst(tmp_path, short_spec):
    pytest.importorskip("optuna")
    study = str(tmp_path / "arm.study.db")
    app = OrccadApp([MISSION], selected=MISSION, campaign={"db": study, "workers": 1,
                                                           "spec": short_spec})
    async with app.run_test(size=SIZE) as pilot:
        await _until(pilot, lambda: isinstance(app.screen, CampaignScreen))
        screen = _campaign(app)
        await pilot.press("f")
        assert screen.mode == "falsify"
        await _type(pilot, screen, "prop", "bounded")
        await _type(pilot, screen, "count", "2")
        await pilot.press("s")
        assert screen.process.args[:2] == ["falsify", MISSION]
        await _until(pilot, lambda: screen.state == "finished" and screen.snapshot is not None
                     and screen.snapshot.trials == 2, timeout=WAIT_S, describe=lambda: (
                         f"state {screen.state}, trials "
                         f"{screen.snapshot and screen.snapshot.trials}, exit status "
                         f"{screen.process.returncode}: {screen.process.error_text()[-400:]}"))
        snapshot = screen.snapshot
        assert snapshot.best == min(c.robustness for c in snapshot.candidates)
        status = _text(screen, "#campaign-status")
        assert "falsification of bounded (finished): 2/2 trials" in status
        assert "best robustness" in status
        await pilot.press("enter")
        await _until(pilot, lambda: any(isinstance(s, RunScreen) for s in app.screen_stack))
        run = _run_screen(app)
        assert run.session.setting == snapshot.candidates[0].setting
        await _until(pilot, lambda: run.finished)  # 0.5 s at 1×


def test_reading_a_database_never_writes_it(tmp_path):
    """The screen reads a campaign's or a study's database while the command writes it. A
    reader that created the tables raced the command creating them (optuna: "table studies
    already exists" ended a falsification at its start), and changed a file it was only shown."""
    pytest.importorskip("optuna")
    new = tmp_path / "new.db"  # a study being created: no table yet
    new.touch()
    assert read_study(str(new), SPEC, "bounded", 0.5, budget=2).trials == 0
    assert new.stat().st_size == 0
    other = tmp_path / "other.db"
    with sqlite3.connect(other) as db:
        db.execute("CREATE TABLE t (x)")
    before = other.read_bytes()
    with pytest.raises(OrccadError, match=r"not a campaign database \(no table campaign\)"):
        read_campaign(str(other))
    with pytest.raises(OrccadError, match=r"not an optuna study database \(no table studies\)"):
        read_study(str(other), SPEC, "bounded", 0.5, budget=2)
    assert other.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["new.db", "other.db"]


def test_a_study_is_read_whatever_characters_its_path_holds(tmp_path):
    optuna = pytest.importorskip("optuna")
    odd = tmp_path / "a b#c%d" / "s%2.db"
    odd.parent.mkdir()
    optuna.create_study(storage=f"sqlite:///{odd}", study_name="arm-bounded-0")
    assert read_study(str(odd), SPEC, "bounded", 0.5, budget=2).trials == 0
    text = odd.parent / "s.db"
    text.write_text("not sqlite", encoding="utf-8")
    with pytest.raises(OrccadError, match="not an optuna study database"):
        read_study(str(text), SPEC, "bounded", 0.5, budget=2)



def _hostile_databases(folder) -> dict[str, tuple[str, str]]:
    """Files given as the console's ``--db``: name -> (path, what the screen says)."""
    empty = folder / "empty.db"
    empty.touch()
    text = folder / "text.db"
    text.write_text("not a database\n", encoding="utf-8")
    other = folder / "other.db"
    with contextlib.closing(sqlite3.connect(other)) as db:
        db.execute("CREATE TABLE campaign (x)")
        db.commit()
    fifo = folder / "fifo.db"
    os.mkfifo(fifo)
    locked = folder / "locked.db"
    with contextlib.closing(sqlite3.connect(locked)) as db:
        db.execute("CREATE TABLE t (x)")
        db.commit()
    return {"empty": (str(empty), "an empty file, not a campaign database"),
            "not SQLite": (str(text), "not an SQLite database (it does not begin with "
                                      "SQLite's header), so not a campaign database"),
            "another program's": (str(other), "not a campaign database (its table campaign "
                                              "has the columns x"),
            "a FIFO": (str(fifo), "a FIFO, not a regular file"),
            "locked": (str(locked), "locked by another program (database is locked)")}


@pytest.fixture
def locker():
    """Hold an exclusive lock on a database, as another program writing it does."""
    held = []

    def lock(path: str) -> None:
        db = sqlite3.connect(path, isolation_level=None)
        db.execute("BEGIN EXCLUSIVE")
        held.append(db)

    yield lock
    for db in held:
        db.close()


def test_each_unreadable_database_is_one_located_message_and_nothing_is_written(
        tmp_path, locker, monkeypatch):
    """Issue 34 item 10: on main the empty and the non-SQLite file said 'no table campaign'
    and 'file is not a database', the FIFO 'no such file', the locked one 'not a campaign
    database (database is locked)', and reading a campaign's database left its -wal and -shm
    beside it."""
    from orccad_app.tui import campaigns

    monkeypatch.setattr(campaigns, "LOCK_WAIT_S", 0.05)
    hostile = _hostile_databases(tmp_path)
    locker(hostile["locked"][0])
    real = tmp_path / "campaign.db"
    CampaignStore(str(real)).close()  # a WAL database, its writer gone
    before = sorted(p.name for p in tmp_path.iterdir())
    for name, (path, said) in hostile.items():
        with pytest.raises(OrccadError) as refused:
            read_campaign(path)
        assert refused.value.message.startswith(f"{path}: {said}"), name
    with pytest.raises(OrccadError, match="no campaign recorded in it"):
        read_campaign(str(real))
    assert sorted(p.name for p in tmp_path.iterdir()) == before  # no -wal, no -shm


@pytest.mark.parametrize("name", ["empty", "not SQLite", "another program's", "a FIFO",
                                  "locked"])
@pilot_test
async def test_the_console_opened_on_an_unreadable_database_says_so_once(tmp_path, locker,
                                                                        monkeypatch, name):
    from orccad_app.tui import campaigns

    monkeypatch.setattr(campaigns, "LOCK_WAIT_S", 0.05)
    path, said = _hostile_databases(tmp_path)[name]
    if name == "locked":
        locker(path)
    app = OrccadApp([], campaign={"db": path})
    async with app.run_test(size=SIZE) as pilot:
        await _until(pilot, lambda: bool(app._notifications),
                     describe=lambda: _text(app.screen, "#campaign-status"))
        await pilot.pause(0.3)  # a second message would come by now
        messages = [n.message for n in app._notifications]
        assert len(messages) == 1 and f"{path}: {said}" in messages[0], messages
        assert "Traceback" not in messages[0]
        status = _text(app.screen, "#campaign-status")
        assert "missions/" not in status  # the database's own mission, not the browser's


def test_orccad_tui_db_on_a_fifo_is_bad_input_said_as_such(tmp_path):
    fifo = tmp_path / "fifo.db"
    os.mkfifo(fifo)
    result = subprocess.run([sys.executable, "-m", "orccad_app", "tui", "--db", str(fifo)],
                            capture_output=True, text=True, timeout=60,
                            stdin=subprocess.DEVNULL)
    assert result.returncode == 2
    assert f"--db {fifo}: a FIFO, not a regular file" in result.stderr
