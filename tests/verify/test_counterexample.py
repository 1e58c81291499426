"""Counterexamples are scripts that ``orccad react --composed`` replays to the violation."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

from orccad_app.pipeline import load
from orccad_app.reactive.runtime import Reactor
from orccad_app.reactive.script import parse_script
from orccad_app.robottask.labels import RtLabel
from orccad_app.verify.checker import check_mission
from orccad_app.verify.formula import from_ast
from orccad_app.verify.lasso import holds_on_lasso

from .conftest import CORPUS, ROOT

FALSE = ROOT / "missions" / "false_property.orc"


def orccad(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "orccad_app.cli", *args], capture_output=True,
                          text=True, cwd=ROOT)


def test_check_exits_1_and_its_script_replays_to_the_violation(tmp_path):
    script = tmp_path / "cex.in"
    result = orccad("check", str(FALSE), "--counterexample", str(script))
    assert result.returncode == 1, result.stderr
    assert "FAIL  property placed_after_approach" in result.stdout
    assert "ok    property one_task_at_a_time" in result.stdout
    replay = orccad("react", str(FALSE), "--composed", "--inputs", str(script), "--jsonl")
    assert replay.returncode == 0, replay.stderr
    records = [json.loads(line) for line in replay.stdout.splitlines()]
    # the violation: Placed is emitted, and Approach never had its good end
    assert "Placed" in records[-1]["outputs"]
    assert not any("Approach.good_end" in r["outputs"] for r in records)


def _letters(program, mission, text, automaton):
    """The atoms true in each replayed instant (the meaning of docs/verification.md)."""
    reactor = Reactor(automaton)
    letters, states = [], []
    status = "running"
    for instant in parse_script(text, "cex.in", automaton.inputs):
        reaction = reactor.react(instant.inputs, instant.time_ns)
        atoms = {("sig", n) for n in (*instant.inputs, *reaction.outputs)}
        for name in reaction.outputs:
            for suffix, kind in ((".start", "started"), (".good_end", "ended"),
                                 (".raised", "raised")):
                if name.endswith(suffix):
                    atoms.add((kind, name[: -len(suffix)]))
        atoms |= {("active", label.task) for label in reactor.labels if isinstance(label, RtLabel)}
        if status == "running" and reaction.status != "running":
            atoms.add(("status", reaction.status))
        status = reaction.status
        letters.append(frozenset(atoms))
        states.append((reaction.state, dict(reactor.store.vars)))
    return letters, states


def _failures():
    for path in [FALSE, *sorted(CORPUS.glob("*.orc"))]:
        source = load(path)
        for mission in source.program.missions:
            report = check_mission(source.program, mission, builtins=False)
            for outcome in report.outcomes:
                if not outcome.holds:
                    yield pytest.param(source, mission, report, outcome,
                                       id=f"{mission.name}.{outcome.name}")


@pytest.mark.parametrize("source,mission,report,outcome", list(_failures()))
def test_every_counterexample_replays_and_violates_its_property(source, mission, report,
                                                                 outcome):
    script = outcome.script
    assert script.replayed, script.note
    prop = next(p for p in source.program.properties if p.name == outcome.name
                and p.mission in (None, mission.name))
    letters, states = _letters(source.program, mission, script.text(),
                               report.composition.automaton)
    assert len(letters) == len(script.lines)
    formula = from_ast(prop.formula)
    if script.loop_start is None:  # a finite run: the last instant breaks 'always P'
        assert not holds_on_lasso(formula, letters, [letters[-1]])
    else:
        start = script.loop_start
        before = states[start - 1][0] if start else report.composition.automaton.initial
        assert states[-1][0] == before, "the loop must come back to where it started"
        assert not holds_on_lasso(formula, letters[:start], letters[start:])


def test_a_deadlock_is_reported_with_where_it_is_stuck(tmp_path):
    path = tmp_path / "stuck.orc"
    path.write_text("mission Stuck {\n  input Go;\n  output Done;\n  await Go;\n"
                    "  signal Never { await Never; }\n  emit Done;\n}\n")
    result = orccad("check", str(path))
    assert result.returncode == 1
    assert "FAIL  built-in no-deadlock" in result.stdout
    assert "stuck.orc:5:" in result.stdout
    assert "| Go" in result.stdout  # the run to the stuck state


def test_bad_input_exits_2_without_traceback(tmp_path):
    path = tmp_path / "bad.orc"
    path.write_text("mission M { output O; emit O; }\nproperty M.p: always (O -> once Q);\n")
    result = orccad("check", str(path))
    assert result.returncode == 2
    assert "unknown signal 'Q'" in result.stderr and "Traceback" not in result.stderr
