"""A run cut by its horizon while the ``on fatal`` recovery runs is ``recovering``, not
``aborted`` (issue 28, 3): the docs describe ``aborted`` as an ended mission."""

from __future__ import annotations

import json

from orccad_app.campaign.adapter import outcome_label
from orccad_app.cli import main

AUV = "missions/auv_survey.orc"


def _run(capsys, *args: str) -> tuple[int, dict, str]:
    status = main(["run", AUV, "--seed", "0", "--inject", "auv.leak=1@100", *args])
    captured = capsys.readouterr()
    return status, captured.out, captured.err


def test_a_recovery_cut_by_the_horizon_is_recovering(capsys, monkeypatch):
    monkeypatch.chdir(__import__("pathlib").Path(__file__).resolve().parents[2])
    status, out, err = _run(capsys, "--until", "105", "--json")
    report = json.loads(out)
    assert status == 1
    assert (report["status"], report["reason"]) == ("recovering", "Leak")
    surfacing = [t for t in report["robot_tasks"] if t["name"] == "Surface"]
    assert surfacing and surfacing[-1]["outcome"] == "running"
    status, out, err = _run(capsys, "--until", "105")
    assert out.startswith("mission AuvSurvey: recovering (Leak)\n"
                          "  aborted by Leak; its 'on fatal' recovery was still running at 105 s")
    assert "its 'on fatal' recovery cut by the horizon (status recovering)" in err


def test_a_finished_recovery_is_aborted(capsys, monkeypatch):
    monkeypatch.chdir(__import__("pathlib").Path(__file__).resolve().parents[2])
    status, out, _ = _run(capsys, "--json")
    report = json.loads(out)
    assert status == 1 and (report["status"], report["reason"]) == ("aborted", "Leak")
    assert report["robot_tasks"][-1]["outcome"] == "good_end"  # the surfacing ended


def test_campaign_outcomes_tell_them_apart():
    assert outcome_label("recovering", "Leak") == "recovering(Leak)"
    assert outcome_label("aborted", "Leak") == "aborted(Leak)"
