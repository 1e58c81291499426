"""From proof to run without the console: ``orccad check --replay P`` prints a counterexample
instant by instant, ``--counterexample OUT`` writes it, ``orccad run --inject-from OUT`` runs
it against the plant (docs/verification.md)."""

from __future__ import annotations

import json

import pytest

from orccad_app.mission.scripted import instant_times, script_injections
from orccad_app.pipeline import load, select_mission
from orccad_app.reactive.script import Instant
from orccad_app.verify.checker import check_mission
from orccad_app.verify.replay import FAILS, LOOPS, replay, script_instants

from .conftest import ROOT
from .test_check_cli import orccad

FALSE = "missions/false_property.orc"


def _report():
    source = load(str(ROOT / FALSE))
    return check_mission(source.program, select_mission(source, None))


def test_a_replay_shows_each_instant_where_the_mission_waits_and_the_failing_one():
    report = _report()
    outcome = next(o for o in report.outcomes if o.name == "placed_after_approach")
    steps = replay(report.composition, outcome).steps
    assert [dict(s.inputs) for s in steps] == [{}, {"Go": None},
                                              {"Approach.TrackingLost": None}, {}]
    assert steps[0].lines_in(FALSE) == [40]  # await Go
    assert [t.task for t in steps[1].tasks] == ["Approach"] and steps[1].run_lines_in(FALSE)
    assert "TrackingLost.raised" in steps[2].outputs and "Placed" in steps[3].outputs
    assert [s.mark for s in steps] == ["", "", "", FAILS] and steps[3].status == "done"


def test_a_liveness_counterexample_marks_its_loop():
    report = _report()
    outcome = next(o for o in report.outcomes if o.name == "eventually_placed")
    result = replay(report.composition, outcome)
    assert result.loop_start == 1 and result.steps[1].mark == LOOPS and result.failing == 1


def test_instants_are_one_reaction_tick_apart_at_least():
    instants = [Instant(1, {}, 0), Instant(2, {"Go": None}, 0),
                Instant(3, {"Approach.TrackingLost": None}, 0), Instant(4, {}, 10**9),
                Instant(5, {"Go": None}, None)]
    assert instant_times(instants, 10**6) == [0, 10**6, 2 * 10**6, 10**9, 10**9 + 10**6]
    injections = script_injections(instants, 10**6)
    assert [(i.name, i.time_ns) for i in injections] == [
        ("Go", 10**6), ("Approach.TrackingLost", 2 * 10**6), ("Go", 10**9 + 10**6)]
    report = _report()
    outcome = next(o for o in report.outcomes if o.name == "placed_after_approach")
    assert [i.inputs for i in script_instants(outcome.script)] == [
        {}, {"Go": None}, {"Approach.TrackingLost": None}, {}]


def test_check_replay_prints_the_steps_and_writes_the_script(tmp_path):
    out = tmp_path / "cex.in"
    result = orccad("check", FALSE, "--replay", "placed_after_approach",
                    "--counterexample", str(out))
    assert result.returncode == 1, result.stderr
    text = result.stdout
    assert "instant 2 at 0 s\n  inputs:  Go\n" in text
    assert "waiting at false_property.orc:40  await Go;" in text
    assert f"instant 4 at 1 s   <- {FAILS}" in text
    assert f"--inject-from {out}" in text
    assert "@0 Go" in out.read_text()


def test_check_replay_of_a_holding_or_unknown_property():
    holds = orccad("check", FALSE, "--replay", "one_task_at_a_time")
    assert holds.returncode == 0 and "holds: no counterexample" in holds.stdout
    unknown = orccad("check", FALSE, "--replay", "nope")
    assert unknown.returncode == 2 and "no such property" in unknown.stderr
    assert "placed_after_approach" in unknown.stderr and "Traceback" not in unknown.stderr


def test_run_inject_from_runs_the_counterexample_against_the_plant(tmp_path):
    out = tmp_path / "cex.in"
    orccad("check", FALSE, "--replay", "placed_after_approach", "--counterexample", str(out))
    result = orccad("run", FALSE, "--inject-from", str(out), "--json")
    report = json.loads(result.stdout)
    injected = [(i["name"], i["time_s"], i["by"]) for i in report["injections"]]
    assert injected == [("Go", 0.001, f"--inject-from {out}"),
                        ("Approach.TrackingLost", 0.002, f"--inject-from {out}")]
    verdicts = {p["name"]: p["verdict"] for p in report["properties"]}
    assert verdicts["placed_after_approach"] == "false"  # the plant run violates it too
    assert result.returncode == 1


@pytest.mark.parametrize("script, message", [("Nope\n", "'Nope' is not an input signal"),
                                             ("@2\n@1 Go\n", "goes backwards")])
def test_run_inject_from_refuses_a_bad_script(tmp_path, script, message):
    bad = tmp_path / "bad.in"
    bad.write_text(script)
    result = orccad("run", FALSE, "--inject-from", str(bad))
    assert result.returncode == 2 and message in result.stderr
    assert f"{bad}:" in result.stderr and "Traceback" not in result.stderr
