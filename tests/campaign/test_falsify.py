"""``orccad falsify``: optuna finds a violating setting; its replay command reproduces the
run and its trace bit for bit; the study resumes."""

from __future__ import annotations

import json
import shlex

import pytest

from .conftest import AUV, orccad

SPEC = """\
mission = "AuvSurvey"
until_s = 40
signals = ["auv.depth"]

[[inject]]
event = "auv.depth_bias=U(-8, 0)@U(8, 12)"   # reads too shallow: the vehicle dives deeper
probability = 0.5

[[check]]
name = "near_target"
metric = "max(auv.depth)"
below = 16.0
"""


@pytest.mark.slow
def test_falsify_finds_a_violation_and_its_replay_reproduces_the_trace(tmp_path):
    spec = tmp_path / "f.toml"
    spec.write_text(SPEC, encoding="utf-8")
    trace = tmp_path / "worst.csv"
    result = orccad("falsify", AUV, "--spec", str(spec), "--property", "near_target",
                    "--budget", "6", "--workers", "1", "--trace", str(trace), "--json",
                    cwd=tmp_path)
    assert result.returncode == 1, result.stderr  # a violation was found
    data = json.loads(result.stdout)
    assert data["violated"] and data["robustness"] < 0 and data["first_violation"] is not None
    assert any(i.startswith("auv.depth_bias=") for i in data["setting"]["injections"])
    replay = shlex.split(data["replay"])
    assert replay[:2] == ["orccad", "run"] and replay[-2:] == ["--trace", str(trace)]
    again = tmp_path / "again.csv"
    rerun = orccad(*replay[1:-2], "--trace", str(again), "--json", cwd=tmp_path)
    assert json.loads(rerun.stdout)["status"] == data["status"]
    assert again.read_bytes() == trace.read_bytes()


@pytest.mark.slow
def test_the_study_resumes_and_bad_input_is_refused(tmp_path):
    spec = tmp_path / "f.toml"
    spec.write_text(SPEC, encoding="utf-8")
    study = tmp_path / "study.db"
    common = ["falsify", AUV, "--spec", str(spec), "--property", "near_target", "--workers",
              "1", "--sampler", "random", "--study", str(study), "--json"]
    first = orccad(*common, "--budget", "2", cwd=tmp_path)
    assert json.loads(first.stdout)["trials"] == 2
    refused = orccad(*common, "--budget", "2", cwd=tmp_path)
    assert refused.returncode == 2 and "--resume" in refused.stderr
    resumed = orccad(*common, "--budget", "2", "--resume", cwd=tmp_path)
    assert json.loads(resumed.stdout)["trials"] == 4
    unknown = orccad("falsify", AUV, "--spec", str(spec), "--property", "nope", cwd=tmp_path)
    assert unknown.returncode == 2 and "near_target" in unknown.stderr
