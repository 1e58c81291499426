"""Issue 33's acceptance: ``orccad check`` proves a mission of 8 robots × 4 Robot-Tasks
(390 626 reachable control states) symbolically, with a false property among its lines, and
``orccad run --inject-from`` replays that property's counterexample against the plant."""

from __future__ import annotations

import importlib.util
import json
import subprocess
import sys

import pytest

from tests.verify.conftest import ROOT, program_of


def _grid(robots: int, tasks: int, **options) -> str:
    spec = importlib.util.spec_from_file_location("bench_missions", ROOT / "bench/_missions.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.robot_grid(robots, tasks, **options)


def orccad(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "orccad_app.cli", *args], capture_output=True,
                          text=True, cwd=ROOT, timeout=600)


def test_8x4_is_proved_and_its_false_property_replays_against_the_plant(tmp_path):
    mission = tmp_path / "grid8x4.orc"
    mission.write_text(_grid(8, 4, false_property=True), encoding="utf-8")
    script = tmp_path / "cex.in"
    checked = orccad("check", str(mission), "--json", "--counterexample", str(script))
    assert checked.returncode == 1, checked.stderr
    report = json.loads(checked.stdout)["missions"][0]
    assert report["engine"] == "symbolic"
    assert report["automaton_states"] == 5 ** 8 + 1
    assert report["model_steps"] is None
    verdicts = {o["name"]: o["holds"] for o in report["outcomes"]}
    assert verdicts == {"fatal-aborts": True, "one-task-per-robot": True, "no-deadlock": True,
                        "tasks-end-first": True, "handover": True, "terminates": True,
                        "never_lost": False}
    lost = next(o for o in report["outcomes"] if o["name"] == "never_lost")
    assert lost["counterexample"]["replayed"] is True
    assert "TrackingLost" in script.read_text(encoding="utf-8")
    ran = orccad("run", str(mission), "--inject-from", str(script), "--json")
    assert ran.returncode == 1, ran.stderr
    run = json.loads(ran.stdout)
    judged = {p["name"]: p["verdict"] for p in run["properties"]}
    assert judged["never_lost"] == "false"


def test_a_mission_beyond_the_budget_is_refused_naming_its_parallel_branches(monkeypatch):
    from orccad_app.diagnostics import OrccadError
    from orccad_app.verify.checker import check_mission
    from orccad_app.verify.symbolic import model

    monkeypatch.setattr(model, "MAX_BDD_NODES", 1_000)
    program = program_of(_grid(4, 2), "grid.orc")
    with pytest.raises(OrccadError) as error:
        check_mission(program, program.missions[0])
    message = str(error.value)
    assert "beyond what can be proved here" in message
    assert "the 4 parallel branches at grid.orc:" in message
    assert error.value.location.file == "grid.orc"
