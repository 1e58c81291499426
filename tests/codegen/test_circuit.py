"""The circuit generator (``orccad codegen --generator circuit``) through the differential
harness: every shipped mission's composed script, the shipped composed-view scripts, the
golden run traces, the Esterel corpus, random programs and robot grids, compiled with the
strict flags and compared with ``Reactor.step`` record by record (state numbers aside)."""

from __future__ import annotations

import itertools
import random
import subprocess
import sys

import pytest
from hypothesis import HealthCheck, assume, given, settings

from orccad_app.cli import main as orccad
from orccad_app.codegen.circuit import circuit_of
from orccad_app.codegen.circuit_reach import reachable
from orccad_app.codegen.circuit_schedule import NotStatic, schedule
from orccad_app.codegen.mission import generate_chosen
from orccad_app.codegen.static_types import CodegenError
from orccad_app.diagnostics import OrccadError
from orccad_app.lang.parser import parse
from orccad_app.pipeline import compose_mission, load
from orccad_app.reactive.compiler import compile_program
from orccad_app.reactive.lower import lower_mission
from orccad_app.robottask.composition import compose
from tests.codegen.cbuild import build
from tests.codegen.circuit_helpers import agree_circuit, circuit_program, mission_circuit
from tests.codegen.conftest import MISSIONS, ROOT, SCRIPTS, SHIPPED, generated
from tests.codegen.test_random_programs import _script
from tests.codegen.test_run_traces import TRACED, _mission, script_of
from tests.reactive.strategies import expand, input_sequences, programs
from tests.reactive.test_esterel_suite import CASES, FOLDER, _trace

_NAMES = itertools.count()
#: HipHop's parvalued (tests/reactive/esterel/): ?I read in a branch before, in the walk, the
#: emission of I in a parallel one — the engine makes the read wait: no static order
NOT_STATIC = """mission parvalued {
    output J : int;
    signal I : int { par { if I { emit J(?I); } } || { emit I(5); } }
}
"""


def _circuit(stem: str, mission: str):
    made = generated(stem, mission)
    return made.composition.automaton, mission_circuit(made.composition, stem)


@pytest.mark.parametrize("stem,mission", SHIPPED)
def test_shipped_mission_circuit_agrees(stem, mission):
    automaton, program = _circuit(stem, mission)
    agree_circuit(automaton, program, SCRIPTS / f"{stem}.{mission}.in")


@pytest.mark.parametrize("stem,mission", SHIPPED)
def test_circuit_main_prints_what_react_composed_prints(stem, mission, capsys):
    _automaton, program = _circuit(stem, mission)
    script = SCRIPTS / f"{stem}.{mission}.in"
    status = orccad(["react", str(MISSIONS / f"{stem}.orc"), "--mission", mission,
                     "--composed", "--jsonl", "--inputs", str(script)])
    expected = capsys.readouterr().out
    done = subprocess.run([str(build(program)), str(script)], capture_output=True, text=True,
                          timeout=60)
    assert done.stdout == expected
    assert done.returncode == status


@pytest.mark.parametrize("script,stem,mission", [("abro.in", "abro", "ABRO"),
                                                 ("arm_pid_composed.in", "arm_pid", "ArmPID")])
def test_shipped_composed_scripts_agree(script, stem, mission):
    automaton, program = _circuit(stem, mission)
    agree_circuit(automaton, program, MISSIONS / script)


@pytest.mark.parametrize("case", TRACED, ids=[c.name for c in TRACED])
def test_recorded_run_inputs_agree_in_circuit(case, tmp_path):
    automaton, program = _circuit(*_mission(case.argv))
    path = tmp_path / f"{case.name}.in"
    path.write_text(script_of(case))
    agree_circuit(automaton, program, path)


@pytest.mark.parametrize("name", CASES)
def test_esterel_trace_through_circuit(name, tmp_path):
    program = parse((FOLDER / f"{name}.orc").read_text(), f"{name}.orc")
    kernel = lower_mission(program, program.missions[-1])
    automaton = compile_program(kernel)
    try:
        generated_c = circuit_program(kernel, "c_" + name.replace("-", "_"))
    except NotStatic:
        pytest.skip("no static order of its data events")
    script = tmp_path / f"{name}.in"
    script.write_text("".join(" ".join(sorted(i)) + "\n" for i, _ in _trace(name)))
    agree_circuit(automaton, generated_c, script)


_RANDOM = dict(deadline=None, derandomize=True, database=None,
               suppress_health_check=[HealthCheck.filter_too_much, HealthCheck.too_slow,
                                      HealthCheck.data_too_large,
                                      HealthCheck.function_scoped_fixture])


def _random_program_agrees(program, sequence, tmp_path_factory) -> None:
    kernel = expand(program)
    try:
        automaton = compile_program(kernel, max_states=300, defer_double_emissions=True)
        generated_c = circuit_program(kernel, "random")
    except (OrccadError, CodegenError, NotStatic):
        assume(False)  # refused, too big, no C type or no static order
    path = tmp_path_factory.mktemp("c", numbered=True) / f"c{next(_NAMES)}.in"
    path.write_text(_script(sequence, program.relations))
    agree_circuit(automaton, generated_c, path)


@settings(max_examples=15, **_RANDOM)
@given(program=programs(), sequence=input_sequences())
def test_random_programs_agree_in_circuit(program, sequence, tmp_path_factory):
    _random_program_agrees(program, sequence, tmp_path_factory)


@pytest.mark.fuzz_long
@settings(max_examples=80, **_RANDOM)
@given(program=programs(), sequence=input_sequences())
def test_many_random_programs_agree_in_circuit(program, sequence, tmp_path_factory):
    """80 programs: one of them (a suspend on a data test around a sustain, in a loop)
    found that a wire computed before a data test is evaluated must be written again
    after it (the restricted functions share nodes reading the test)."""
    _random_program_agrees(program, sequence, tmp_path_factory)


def _grid(robots: int, tasks: int):
    sys.path.insert(0, str(ROOT / "bench"))
    from _missions import robot_grid

    program = parse(robot_grid(robots, tasks), f"grid{robots}x{tasks}.orc")
    return compose(program, program.missions[0], lazy=True)


@pytest.mark.parametrize("robots,tasks", [(2, 2), (3, 3), (4, 2)])
def test_robot_grid_circuit_agrees(robots, tasks, tmp_path):
    composition = _grid(robots, tasks)
    program = mission_circuit(composition, f"grid{robots}x{tasks}")
    names = [s.name for s in composition.automaton.inputs]
    rng = random.Random(robots * 10 + tasks)
    lines = []
    for instant in range(400):  # 10 ms apart: tasks of 1 s end, exceptions fire at random
        present = [n for n in names if rng.random() < 0.01]
        lines.append(" ".join([f"@{instant * 0.01!r}", *present]))
    path = tmp_path / "grid.in"
    path.write_text("\n".join(lines) + "\n")
    records = agree_circuit(composition.automaton, program, path)
    assert any(r.get("outputs") for r in records)


def test_auto_writes_the_circuit_past_the_explicit_budget(tmp_path):
    composition = _grid(3, 3)
    program = generate_chosen(composition, "grid")
    assert program.generator == "circuit"
    assert "generator: circuit: the explicit automaton has more than" in program.header


def test_auto_keeps_the_smaller_explicit_automaton():
    source = load(MISSIONS / "abro.orc")
    composition = compose_mission(source, source.program.missions[0], lazy=True)
    program = generate_chosen(composition, "abro")
    assert program.generator == "explicit"
    assert "generator: explicit automaton: " in program.header
    assert "lines of C, the circuit's" in program.header


def test_auto_falls_back_where_the_order_is_not_static(tmp_path):
    path = tmp_path / "parvalued.orc"
    path.write_text(NOT_STATIC)
    source = load(path)
    composition = compose_mission(source, source.program.missions[0], lazy=True)
    program = generate_chosen(composition, "parvalued")
    assert program.generator == "explicit"
    assert "no static order: a value is read before" in program.header


def test_forced_circuit_without_static_order_is_a_located_error(tmp_path, capsys):
    path = tmp_path / "parvalued.orc"
    path.write_text(NOT_STATIC)
    status = orccad(["codegen", str(path), "--generator", "circuit",
                     "-o", str(tmp_path / "out")])
    err = capsys.readouterr().err
    assert status == 2
    assert "static order" in err and "parvalued.orc:3:" in err
    assert not (tmp_path / "out").exists()


def test_the_reachable_states_simplify_the_circuit():
    """auv_survey: its next-state BDDs over every valuation of 33 registers gave 36 900
    lines of C; restricted to the reachable valuations, about 2 000."""
    made = generated("auv_survey", "AuvSurvey")
    program = mission_circuit(made.composition, "auv_survey")
    assert program.source.count("\n") < 3_000


def test_the_static_order_needs_hold_only_on_the_reachable_states():
    """arm_recovery's ``every 1 s`` counter: its events may run in the other order only in
    register valuations no run reaches."""
    made = generated("arm_recovery", "ArmRecovery")
    circuit = circuit_of(made.composition.automaton.program)
    try:
        with pytest.raises(NotStatic, match="becomes sure after a later one"):
            schedule(circuit, circuit.manager.true)
        assert schedule(circuit, reachable(circuit))
    finally:
        circuit.manager.release(circuit)
