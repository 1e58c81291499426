"""Issue 34 (items 11 and 12): every size a user types into a campaign or a falsification is
checked before the work, and a spec never silently means something else."""

from __future__ import annotations

import sqlite3
from pathlib import Path

import pytest

from tests.campaign.conftest import AUV, LEAK_SPEC, ROOT
from tests.fuzz.harness import check_outcome, run_orccad

PID = str(ROOT / "missions" / "arm_pid.orc")
WAYPOINTS = str(ROOT / "missions" / "auv_waypoints.orc")


def _refused(outcome, *fragments: str) -> None:
    check_outcome(outcome)
    assert outcome.status == 2, (outcome.status, outcome.err)
    for fragment in fragments:
        assert fragment in outcome.err, outcome.err


def _spec(tmp_path: Path, text: str = LEAK_SPEC, name: str = "s.toml") -> str:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return str(path)


def _runs(db: Path) -> int:
    with sqlite3.connect(db) as connection:
        return connection.execute("SELECT COUNT(*) FROM runs").fetchone()[0]


# -- item 11: budgets before the work ----------------------------------------------------

def test_a_falsification_budget_past_the_samplers_bound_is_refused():
    from orccad_app.campaign.falsify import MAX_TRIALS
    from orccad_app.commands import falsify

    assert falsify.MAX_TRIALS == MAX_TRIALS  # the command's mirror of the bound
    outcome = run_orccad(["falsify", AUV, "--spec", "s.toml", "--property", "shallow",
                          "--budget", str(MAX_TRIALS + 1)])
    _refused(outcome, f"expected a whole number in [1, {MAX_TRIALS}]")


def test_a_resumed_study_counts_its_trials_in_the_budget(tmp_path, monkeypatch):
    pytest.importorskip("optuna")
    from orccad_app.campaign import falsify
    from orccad_app.campaign.spec import load_spec
    from orccad_app.diagnostics import OrccadError

    spec = load_spec(_spec(tmp_path))
    storage = f"sqlite:///{tmp_path / 'study.db'}"
    falsify.Falsifier(AUV, spec, "shallow", storage=storage).run(2, workers=1)
    monkeypatch.setattr(falsify, "MAX_TRIALS", 3)
    again = falsify.Falsifier(AUV, spec, "shallow", storage=storage, resume=True)
    with pytest.raises(OrccadError, match="2 trials in the study and 2 more exceed the 3"):
        again.run(2, workers=1)
    assert len(again.study.trials) == 2  # refused before a trial was asked


def test_a_pool_never_has_more_workers_than_runs(tmp_path, monkeypatch):
    from orccad_app.campaign import executor, falsify
    from orccad_app.campaign.runner import Campaign, CampaignOptions
    from orccad_app.campaign.spec import load_spec

    spec = load_spec(_spec(tmp_path))
    campaign = Campaign(AUV, spec, CampaignOptions(runs=2, workers=64,
                                                   db=str(tmp_path / "c.db")))
    result = campaign.run()
    assert len(result.records) == 2
    assert campaign.backend.workers == 2
    pytest.importorskip("optuna")
    pools: list[int] = []

    def spy(workers, cluster, runs=None):
        backend = executor.make_backend(workers, cluster, runs)
        pools.append(backend.workers)
        return backend

    monkeypatch.setattr(falsify, "make_backend", spy)
    falsify.Falsifier(AUV, spec, "shallow").run(3, workers=200)
    assert pools == [3]


@pytest.mark.parametrize("report, message", [
    ("{spec}/r.html", "not a folder"),
    ("{tmp}/missing/r.html", "no such folder"),
    ("{spec}/sub/folder", "not a folder"),
    ("{spec}", "not a folder (a report folder, or a file ending in .html)"),
    ("{tmp}", None),  # an existing folder is a report folder: accepted
])
def test_the_report_path_is_checked_before_the_first_run(tmp_path, report, message):
    spec = _spec(tmp_path)
    db = tmp_path / "c.db"
    path = report.format(spec=spec, tmp=tmp_path)
    if message is None:
        path = str(tmp_path / "a.html")
        (tmp_path / "a.html").mkdir()
        message = "is a folder, not a file"
    outcome = run_orccad(["campaign", AUV, "--spec", spec, "--runs", "3", "--db", str(db),
                          "--report", path])
    _refused(outcome, f"--report {path}", message)
    assert not db.exists()  # no run was made


@pytest.mark.parametrize("trace, message", [
    ("{spec}/t.csv", "not a folder"),
    ("{tmp}/missing/t.csv", "no such folder"),
    ("{tmp}", "is a folder, not a file"),
    ("{tmp}/t.txt", "unknown trace format '.txt'"),
])
def test_the_falsification_trace_is_checked_before_the_first_trial(tmp_path, trace, message):
    spec = _spec(tmp_path)
    study = tmp_path / "study.db"
    path = trace.format(spec=spec, tmp=tmp_path)
    outcome = run_orccad(["falsify", AUV, "--spec", spec, "--property", "shallow",
                          "--budget", "3", "--study", str(study), "--trace", path])
    _refused(outcome, f"--trace {path}", message)
    assert not study.exists()  # no trial was made


def test_a_period_drawn_beside_a_round_end_is_refused_before_the_first_run(tmp_path):
    # both ends of U(1, 2) ms are commensurate with the mission's 1 ms and 5 ms periods, but
    # a draw such as 1.00001 ms makes the timers' instant 10 ns: every such run was refused
    # by its plan in the worker, a 'crashed' run, and the campaign ended in exit status 3
    text = ('mission = "ArmPID"\nuntil_s = 0.05\n[timing]\n'
            '"TrackPID.ctrl.period_ms" = "U(1, 2)"\n')
    db = tmp_path / "c.db"
    outcome = run_orccad(["campaign", PID, "--spec", _spec(tmp_path, text), "--runs", "4",
                          "--db", str(db)], budget_s=60)
    _refused(outcome, "s.toml:4:1", "draws periods such as 1.00001 ms",
             "greatest common divisor of 10 ns", "draw a period with choice(...)")
    assert not db.exists()  # refused before the database was made
    text = text.replace('"U(1, 2)"', '"choice(1, 2)"')
    outcome = run_orccad(["campaign", PID, "--spec", _spec(tmp_path, text), "--runs", "2",
                          "--db", str(tmp_path / "d.db")], budget_s=60)
    check_outcome(outcome, budget_s=60)
    assert outcome.status == 0, outcome.err


def test_a_half_megabyte_value_in_a_spec_is_cut_in_the_message(tmp_path):
    big = "[" + ",".join(["1.5"] * 100_000) + "]"
    for text in (f'mission = "AuvSurvey"\nruns = 2\n[params]\n"auv.cb_height_m" = "{big}"\n',
                 f'mission = "AuvSurvey"\nruns = 2\n[[inject]]\nevent = "auv.leak={big}@1"\n',
                 f'mission = "AuvSurvey"\nruns = 2\n[[inject]]\nevent = "{big}"\n'):
        outcome = run_orccad(["campaign", AUV, "--spec", _spec(tmp_path, text), "--db",
                              str(tmp_path / "c.db")])
        _refused(outcome, "s.toml:4:1", " … ", " characters)")
        assert len(outcome.err) < 1000, len(outcome.err)


# -- item 12: campaign specs -------------------------------------------------------------

def test_a_truncated_normal_whose_redraws_would_fail_is_refused():
    from orccad_app.campaign.distributions import (DistributionError, Kind, _MAX_REDRAWS,
                                                   Distribution, parse_distribution)

    for text in ("N(0, 1, 0, 0)", "N(0, 1, -0.01, 0.01)", "N(0.5, 1e300, 0, 1)"):
        with pytest.raises(DistributionError, match="of the normal's probability, less than"):
            parse_distribution(text)
    parse_distribution("N(0, 1, 0, 0.2)")  # 7.9 % of the mass: accepted
    # a distribution that escaped the check says so, never the mean
    import numpy as np

    hopeless = Distribution(Kind.NORMAL, (0.0, 1.0, 50.0, 51.0), "N(0, 1, 50, 51)")
    with pytest.raises(DistributionError, match=f"{_MAX_REDRAWS} redraws all fell outside"):
        hopeless.sample(np.random.default_rng(0))


@pytest.mark.parametrize("value", ["nan", "inf", "-inf"])
def test_a_check_bound_that_is_not_finite_is_refused(tmp_path, value):
    text = LEAK_SPEC.replace("below = 30.0", f"below = {value}")
    outcome = run_orccad(["campaign", AUV, "--spec", _spec(tmp_path, text), "--db",
                          str(tmp_path / "c.db")])
    _refused(outcome, "s.toml:19:1", "below must be a finite number")


def test_a_study_database_is_not_a_campaign_database_nor_the_reverse(tmp_path):
    pytest.importorskip("optuna")
    spec = _spec(tmp_path)
    study = tmp_path / "study.db"
    outcome = run_orccad(["falsify", AUV, "--spec", spec, "--property", "shallow",
                          "--budget", "1", "--study", str(study), "--trace",
                          str(tmp_path / "t.csv")], budget_s=60)
    check_outcome(outcome, budget_s=60)
    tables = _tables(study)
    for resume in ((), ("--resume",)):
        _refused(run_orccad(["campaign", AUV, "--spec", spec, "--runs", "1", "--db",
                             str(study), *resume]),
                 f"{study}: not a campaign database", "studies")
    assert _tables(study) == tables  # nothing was added to it
    db = tmp_path / "c.db"
    check_outcome(run_orccad(["campaign", AUV, "--spec", spec, "--runs", "1", "--db",
                              str(db)], budget_s=60), budget_s=60)
    tables = _tables(db)
    _refused(run_orccad(["falsify", AUV, "--spec", spec, "--property", "shallow",
                         "--budget", "1", "--study", str(db), "--resume"]),
             f"{db}: not an optuna study database", "a campaign database")
    assert _tables(db) == tables


def _tables(path: Path) -> set[str]:
    with sqlite3.connect(path) as connection:
        return {row[0] for row in connection.execute("SELECT name FROM sqlite_master")}


def test_a_vector_injection_in_a_spec_says_what_a_campaign_accepts(tmp_path):
    for event, line in (("Waypoint([15, 0, 5])@1", "a campaign draws numbers, not vectors"),
                        ("Waypoint(1)@1", "Waypoint carries a vector, and a campaign draws "
                                          "numbers only")):
        text = f'mission = "AuvWaypoints"\nuntil_s = 5\n[[inject]]\nevent = "{event}"\n'
        outcome = run_orccad(["campaign", WAYPOINTS, "--spec", _spec(tmp_path, text), "--db",
                              str(tmp_path / "c.db")])
        _refused(outcome, "s.toml:4:1", line, "choice", "--inject 'Waypoint([x, y, ...])@T'")
