"""Sub-mission instances in the automaton's labels, ``orccad compile``'s listing and
``orccad check``'s counterexamples (text and ``--json``)."""

from __future__ import annotations

import json
from pathlib import Path

from orccad_app.cli import main
from orccad_app.pipeline import compile_mission, load, select_mission
from orccad_app.reactive.labels import MissionLabel

GREET = """\
// a library of one sub-mission
mission Greet [input Go; output Hello] {
    await Go;
    emit Hello;
    await Go;
}
"""

MAIN = """\
from "lib/greet.orc" import Greet;

mission Main {
    input Go;
    output Hi;
    run mission Greet [Hello / Hi];
    run mission Greet [Hello / Hi];
}
property Main.greets_once: never (Hi and once previously Hi);
"""


def _files(tmp_path: Path, monkeypatch) -> None:
    (tmp_path / "lib").mkdir()
    (tmp_path / "lib" / "greet.orc").write_text(GREET, encoding="utf-8")
    (tmp_path / "main.orc").write_text(MAIN, encoding="utf-8")
    monkeypatch.chdir(tmp_path)


def test_each_instance_is_labelled_with_its_declaration_and_call_site(tmp_path, monkeypatch):
    _files(tmp_path, monkeypatch)
    source = load("main.orc")
    automaton = compile_mission(source, select_mission(source, None))
    labels = {label for state in automaton.labels for label in state
              if isinstance(label, MissionLabel)}
    assert sorted(label.text() for label in labels) == [
        "Greet#1 (lib/greet.orc:2) inside main.orc:6",
        "Greet#2 (lib/greet.orc:2) inside main.orc:7"]


def test_compile_lists_the_sub_mission_of_each_state(tmp_path, monkeypatch, capsys):
    _files(tmp_path, monkeypatch)
    assert main(["compile", "main.orc", "--format", "summary"]) == 0
    out = capsys.readouterr().out
    assert "; in mission Greet#2 (lib/greet.orc:2) inside main.orc:7)" in out
    assert main(["compile", "main.orc", "--format", "json"]) == 0
    states = json.loads(capsys.readouterr().out)["states"]
    inside = [m for state in states for m in state["sub_missions"]]
    assert {"mission": "Greet", "instance": 2, "defined_at": "lib/greet.orc:2:1",
            "called_at": "main.orc:7:5", "waiting_at": ["lib/greet.orc:3:5"],
            "text": "Greet#2 (lib/greet.orc:2) inside main.orc:7, at lib/greet.orc:3"} in inside


def test_a_counterexample_inside_a_sub_mission_names_the_instance(tmp_path, monkeypatch,
                                                                  capsys):
    _files(tmp_path, monkeypatch)
    assert main(["check", "main.orc", "--counterexample", "cex.in"]) == 1
    out = capsys.readouterr().out
    assert "FAIL  property greets_once" in out
    # after the instant that starts the second instance: where the mission is, and why
    assert "| # in Greet#2 (lib/greet.orc:2) inside main.orc:7, at lib/greet.orc:3" in out
    assert "| # in Greet#1 (lib/greet.orc:2) inside main.orc:6, at lib/greet.orc:5" in out
    # the comment lines do not change the script: it replays to the violation
    script = Path("cex.in").read_text(encoding="utf-8")
    assert "# in Greet#2" in script
    assert main(["react", "main.orc", "--composed", "--inputs", "cex.in", "--jsonl"]) == 0
    outputs = [json.loads(line)["outputs"] for line in capsys.readouterr().out.splitlines()]
    assert [o for o in outputs if "Hi" in o] == [["Hi"], ["Hi"]]


def test_check_json_gives_each_instant_its_sub_missions(tmp_path, monkeypatch, capsys):
    _files(tmp_path, monkeypatch)
    assert main(["check", "main.orc", "--json"]) == 1
    report = json.loads(capsys.readouterr().out)
    assert report["failed"] == 1 and report["holds"] is False
    outcome = next(o for o in report["missions"][0]["outcomes"] if o["name"] == "greets_once")
    instants = outcome["counterexample"]["instants"]
    assert outcome["counterexample"]["replayed"] is True
    assert [[m["text"].split(" (")[0] for m in i["inside"]] for i in instants] == [
        ["Greet#1"], ["Greet#1"], ["Greet#2"], ["Greet#2"]]
    assert instants[-1]["inside"][0]["called_at"] == "main.orc:7:5"
    assert instants[-1]["inputs"] == {"Go": None}


def test_check_json_of_a_mission_that_holds(capsys):
    assert main(["check", "missions/arm_recovery.orc", "--json"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert report["holds"] is True and report["missions"][0]["mission"] == "ArmRecovery"
    assert all(o["counterexample"] is None for o in report["missions"][0]["outcomes"])


def test_a_sub_mission_that_halts_is_no_deadlock(tmp_path, monkeypatch, capsys):
    (tmp_path / "m.orc").write_text("mission Idle [output O] { emit O; halt; }\n"
                                    "mission M { output O; run mission Idle; }\n",
                                    encoding="utf-8")
    monkeypatch.chdir(tmp_path)
    assert main(["check", "m.orc", "--mission", "M"]) == 0, capsys.readouterr().out


def test_a_robot_task_of_a_sub_mission_run_by_on_fatal_belongs_to_on_fatal(capsys):
    # missions/auv_survey.orc's 'on fatal' runs the sub-mission Surfacing: its Surface may
    # stay active when the mission is aborted (built-ins fatal-aborts and tasks-end-first)
    assert main(["check", "missions/auv_survey.orc"]) == 0, capsys.readouterr().out
