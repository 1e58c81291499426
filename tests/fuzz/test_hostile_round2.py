"""Regressions of issue 28's hostile pass over the newest features: every case below hung,
read until memory ran out, ended in an internal error or silently changed what the user wrote;
each now gets a located refusal (exit 2) before any work, or a defined result."""

from __future__ import annotations

import os
import sqlite3
from pathlib import Path

import pytest

from tests.campaign.conftest import LEAK_SPEC
from tests.fuzz.harness import check_outcome, run_orccad

ROOT = Path(__file__).resolve().parents[2]
AUV = str(ROOT / "missions" / "auv_survey.orc")


def _refused(outcome, *fragments: str) -> None:
    check_outcome(outcome)
    assert outcome.status == 2, (outcome.status, outcome.err)
    for fragment in fragments:
        assert fragment in outcome.err, outcome.err


@pytest.fixture
def fifo(tmp_path) -> str:
    path = tmp_path / "pipe.orc"
    os.mkfifo(path)
    return str(path)


def test_a_fifo_or_a_device_is_refused_as_mission_import_spec_and_tui_file(tmp_path, fifo):
    for special in (fifo, "/dev/zero"):
        _refused(run_orccad(["compile", special], budget_s=10), special, "not a regular file")
        _refused(run_orccad(["tui", special], budget_s=10), "not a regular file")
        _refused(run_orccad(["campaign", AUV, "--spec", special, "--db",
                             str(tmp_path / "c.db")], budget_s=10), "not a regular file")
    main = tmp_path / "m.orc"
    main.write_text(f'from "{fifo}" import Homing;\nmission M {{ run mission Homing; }}\n',
                    encoding="utf-8")
    _refused(run_orccad(["compile", str(main)], budget_s=10), "not a regular file")


def _spec(tmp_path, text: str, name: str = "s.toml") -> str:
    path = tmp_path / name
    path.write_bytes(text.encode("utf-8") if isinstance(text, str) else text)
    return str(path)


def _campaign(tmp_path, spec: str, *extra: str):
    return run_orccad(["campaign", AUV, "--spec", spec, "--db", str(tmp_path / "c.db"),
                       *extra], budget_s=30)


def test_a_spec_that_is_not_utf8_gets_a_located_error(tmp_path):
    spec = tmp_path / "s.toml"
    spec.write_bytes(b'mission = "AuvSurvey"\nruns = 3 # \xff\n')
    _refused(_campaign(tmp_path, str(spec)), f"{spec}:2:", "not UTF-8")


@pytest.mark.parametrize("key, value, message", [
    ("runs", "1000000000000", "runs must be an integer in [1, 1000000]"),
    ("until_s", "inf", "until_s must be a number of seconds in (0, 3.1536e+07]"),
    ("until_s", "1e12", "until_s must be a number of seconds"),
    ("until_s", "nan", "until_s must be a number of seconds"),
    ("seed", "123456789012345678901234567890", "seed must be an integer in [0, "),
    ("seeds", '"UI(0, 100000000000000000000)"', "seeds must draw integers in [0, "),
])
def test_campaign_spec_numbers_at_the_edges_are_refused_before_any_run(tmp_path, key, value,
                                                                       message):
    import re

    text = re.sub(rf"^{key} = .*$", f"{key} = {value}", LEAK_SPEC, flags=re.M)
    if f"{key} = {value}" not in text:
        text = text.replace("seed = 5\n", f"seed = 5\n{key} = {value}\n")
    _refused(_campaign(tmp_path, _spec(tmp_path, text)), message)


@pytest.mark.parametrize("args, message", [
    (["--runs", "1000000000000"], "expected a whole number in [1, 1000000]"),
    (["--epsilon", "1e-9"], "more than the 1000000 runs a campaign may make"),
    (["--workers", "1000000"], "expected a whole number in [1, 256]"),
    (["--hypothesis", "P(aborted(Leek)) >= 0.5"], "did you mean aborted(Leak)"),
    (["--hypothesis", "P(dne) >= 0.5"], "did you mean done"),
])
def test_campaign_options_that_would_cost_unbounded_work_or_mean_nothing_are_refused(
        tmp_path, args, message):
    _refused(_campaign(tmp_path, _spec(tmp_path, LEAK_SPEC), *args), message)


def test_foreign_corrupt_and_hostile_databases_are_refused(tmp_path):
    spec = _spec(tmp_path, LEAK_SPEC)
    corrupt = tmp_path / "corrupt.db"
    corrupt.write_bytes(os.urandom(4096))
    foreign = tmp_path / "foreign.db"
    with sqlite3.connect(foreign) as db:
        db.execute("CREATE TABLE runs (id INTEGER, payload BLOB)")
    for path in (corrupt, foreign):
        _refused(run_orccad(["campaign", AUV, "--spec", spec, "--db", str(path), "--resume"],
                            budget_s=30), str(path), "not a campaign database")
    # a campaign database whose row was edited: refused, located at its run
    from orccad_app.campaign.store import SCHEMA
    hostile = tmp_path / "hostile.db"
    with sqlite3.connect(hostile) as db:
        db.executescript(SCHEMA)
        db.execute("INSERT INTO runs VALUES (0, 1, 'done', 'done', NULL, 1.0, NULL, 1.0, 1, "
                   "NULL, '{\"index\": \"zero\"}', 'x')")
    _refused(run_orccad(["campaign", AUV, "--spec", spec, "--db", str(hostile), "--resume"],
                        budget_s=30), f"{hostile}: run 0: not a row a campaign writes")


def test_a_corrupt_or_foreign_study_file_is_refused(tmp_path):
    pytest.importorskip("optuna")
    spec = _spec(tmp_path, LEAK_SPEC)
    corrupt = tmp_path / "study.db"
    corrupt.write_bytes(os.urandom(4096))
    foreign = tmp_path / "foreign.db"
    with sqlite3.connect(foreign) as db:
        db.execute("CREATE TABLE studies (x)")
    for path in (corrupt, foreign):
        _refused(run_orccad(["falsify", AUV, "--spec", spec, "--property", "shallow",
                             "--study", str(path), "--budget", "1"], budget_s=30),
                 "not an optuna study database")


def test_clip_with_its_bounds_swapped_is_refused_at_load(tmp_path):
    text = (ROOT / "missions" / "arm_retune.orc").read_text(encoding="utf-8")
    start = text.index("adjust ")
    end = text.index(";", start)
    target = text[start:end].split("=")[0].strip()  # adjust M.P
    path = tmp_path / "arm_retune.orc"
    path.write_text(text[:start] + f"{target} = clip(1.0, 800.0, 150.0)" + text[end:],
                    encoding="utf-8")
    _refused(run_orccad(["compile", str(path)]), "clip(x, lo, hi) needs lo <= hi")


def test_the_command_line_mirror_of_the_runs_budget_is_the_campaign_s():
    from orccad_app.campaign.spec import MAX_RUNS
    from orccad_app.commands import campaign

    assert campaign.MAX_RUNS == MAX_RUNS


def test_a_timing_finer_than_a_nanosecond_is_refused_not_rounded():
    pid = str(ROOT / "missions" / "arm_pid.orc")
    _refused(run_orccad(["run", pid, "--until", "0.01", "--timing",
                         "TrackPID.ctrl.wcet_ms=0.0000015"]),
             "0.0000015 ms is not a whole number of nanoseconds", "1.5 ns")
    check_outcome(run_orccad(["run", pid, "--until", "0.01", "--json", "--timing",
                              "TrackPID.ctrl.wcet_ms=0.000002"]), json_doc=True)


def test_campaign_timing_draws_are_whole_nanoseconds():
    from orccad_app.campaign.setting import draw_setting
    from orccad_app.campaign.spec import parse_spec
    from orccad_app.mission.overrides import parse_timing

    spec = parse_spec(LEAK_SPEC.replace('"U(0.5, 3)"', '"U(0.0001, 0.0002)"'), "s.toml")
    for index in range(20):
        for text in draw_setting(spec, index, 30.0).timings:
            parse_timing(text)  # refused if it were not whole nanoseconds


def test_sub_missions_expanding_exponentially_are_refused_before_they_are_built(tmp_path):
    lines = ["input A;", "output O;", "mission L0 { await A; emit O; }"]
    for level in range(1, 6):
        lines.append(f"mission L{level} {{ " + f"run mission L{level - 1}; " * 10 + "}")
    lines.append("mission Top { " + "run mission L5; " * 4 + "}")
    path = tmp_path / "exp.orc"
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    outcome = run_orccad(["compile", str(path), "-m", "Top"], budget_s=20)
    _refused(outcome, f"{path}:9:1", "more than 200000 syntax nodes")
    assert outcome.seconds < 10


def test_a_run_whose_reactions_and_jobs_exceed_the_budget_is_refused_before_it_starts(tmp_path):
    # a 1 us period costs ~50 s and 1.4 GB per simulated second: the gcd check alone let it run
    text = (ROOT / "missions" / "arm_pid.orc").read_text(encoding="utf-8")
    path = tmp_path / "arm_pid.orc"
    path.write_text(text.replace("period 1 ms", "period 0.001 ms"), encoding="utf-8")
    outcome = run_orccad(["run", str(path), "--until", "60"], budget_s=30)
    _refused(outcome, "reactions and Module-Task jobs", "more than the 5e+07 a run may cost")
    assert outcome.seconds < 20
    check_outcome(run_orccad(["run", str(path), "--until", "0.002", "--json"], budget_s=60),
                  json_doc=True, budget_s=60)
