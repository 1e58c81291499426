"""Every shipped mission through the generated C: compiled with the strict flags, run on
scripts, equal to the Python reactor record by record.

- ``tests/codegen/scripts/FILE.MISSION.in``: a composed-view script per shipped mission
  (observer events at times, retunes, a loss and its retry, valued inputs, Stop): the generated
  ``PREFIX_main`` prints exactly what ``orccad react --composed --jsonl`` prints, with the same
  exit status;
- ``missions/*.in``: the shipped scripts, each in its view, through ``--trace``: the same
  records plus the state reached and the instant's status.
"""

from __future__ import annotations

import subprocess

import pytest

from orccad_app.cli import main as orccad
from orccad_app.codegen.generate import generate
from orccad_app.pipeline import ABSTRACT, COMPOSED, compile_mission, load
from tests.codegen.cbuild import build, run_trace
from tests.codegen.conftest import MISSIONS, SCRIPTS, SHIPPED, generated
from tests.codegen.differential import first_difference, python_records

#: each shipped script: its mission file and the view it is written for
SHIPPED_SCRIPTS = {
    "abro.in": ("abro", "ABRO", COMPOSED),
    "arm_pid_composed.in": ("arm_pid", "ArmPID", COMPOSED),
    "arm_recovery.in": ("arm_recovery", "ArmRecovery", ABSTRACT),
    "auv_leak.in": ("auv_survey", "AuvSurvey", ABSTRACT),
    "auv_survey.in": ("auv_survey", "AuvSurvey", ABSTRACT),
    "auv_waypoints.in": ("auv_waypoints", "AuvWaypoints", ABSTRACT),
}


def test_every_shipped_mission_has_a_composed_script():
    names = {f"{stem}.{mission}.in" for stem, mission in SHIPPED}
    assert names == {p.name for p in SCRIPTS.glob("*.in")}
    assert set(SHIPPED_SCRIPTS) == {p.name for p in MISSIONS.glob("*.in")}


@pytest.mark.parametrize("stem,mission", SHIPPED)
def test_main_prints_what_react_composed_prints(stem, mission, capsys):
    binary = build(generated(stem, mission).program)
    script = SCRIPTS / f"{stem}.{mission}.in"
    status = orccad(["react", str(MISSIONS / f"{stem}.orc"), "--mission", mission,
                     "--composed", "--jsonl", "--inputs", str(script)])
    expected = capsys.readouterr().out
    done = subprocess.run([str(binary), str(script)], capture_output=True, text=True,
                          timeout=60)
    assert done.stdout == expected
    assert done.returncode == status
    assert len(expected.splitlines()) >= 4


@pytest.mark.parametrize("script", sorted(SHIPPED_SCRIPTS))
def test_shipped_scripts_agree_with_the_reactor(script):
    stem, mission, view = SHIPPED_SCRIPTS[script]
    if view == COMPOSED:
        automaton = generated(stem, mission).composition.automaton
        program = generated(stem, mission).program
    else:
        source = load(MISSIONS / f"{stem}.orc")
        automaton = compile_mission(source, source.program.mission(mission), view=ABSTRACT)
        # the abstract view has no Robot-Task parameters to size a vector input: the
        # composed view's types (same names) give them
        composed = generated(stem, mission).program.types.places
        by_name = {getattr(d, "name", None): t for d, t in composed.items()}
        hints = {s: by_name[s.name] for s in automaton.inputs if s.type == "vector"}
        program = generate(automaton, f"{stem}_abstract", hints=hints)
    path = MISSIONS / script
    expected = python_records(automaton, path.read_text(), str(path))
    got, status, stderr = run_trace(build(program), path)
    assert first_difference(expected, got) is None, first_difference(expected, got)
    assert status in (0, 1), stderr
