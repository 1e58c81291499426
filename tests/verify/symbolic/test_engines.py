"""The symbolic checker gives the explicit checker's verdicts.

On every shipped mission, the verification corpus (whose files name each property's
expected verdict) and generated robot grids, counters exact on both sides (where the symbolic
one has to abstract them, a counter leaving its bits, the reference abstracts them too).
Every symbolic counterexample replays (``Script.replayed``).
"""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest

from orccad_app.pipeline import load
from orccad_app.verify.checker import check_mission
from tests.verify.conftest import program_of

ROOT = Path(__file__).resolve().parents[3]
FILES = sorted([*ROOT.glob("missions/*.orc"), *ROOT.glob("missions/lib/*.orc"),
                *ROOT.glob("tests/verify/corpus/*.orc")])


def _grid():
    spec = importlib.util.spec_from_file_location("bench_missions", ROOT / "bench/_missions.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.robot_grid


def _verdicts(report):
    return [(o.kind, o.name, o.holds) for o in report.outcomes]


def _compare(program, mission):
    symbolic = check_mission(program, mission, engine="symbolic")
    assert symbolic.engine == "symbolic"
    counters = symbolic.symbolic.abstracted is None
    explicit = check_mission(program, mission, engine="explicit", counters=counters)
    assert explicit.engine == "explicit"
    assert _verdicts(symbolic) == _verdicts(explicit)
    for outcome in symbolic.outcomes:
        if not outcome.holds and counters:
            assert outcome.script is not None and outcome.script.replayed, outcome.name
    return symbolic, explicit


@pytest.mark.parametrize("path", FILES, ids=lambda p: str(p.relative_to(ROOT)))
def test_same_verdicts_on_shipped_missions_and_corpus(path):
    source = load(path)
    for mission in source.program.missions:
        _compare(source.program, mission)


def test_corpus_names_are_the_symbolic_verdicts():
    for path in sorted(ROOT.glob("tests/verify/corpus/*.orc")):
        source = load(path)
        for mission in source.program.missions:
            report = check_mission(source.program, mission, engine="symbolic")
            for outcome in report.outcomes:
                if outcome.kind != "property" or report.symbolic.abstracted:
                    continue
                assert outcome.holds == outcome.name.startswith("holds_"), outcome.name


@pytest.mark.parametrize("robots,tasks", [(2, 2), (3, 2), (2, 3)])
def test_same_verdicts_on_robot_grids(robots, tasks):
    program = program_of(_grid()(robots, tasks, false_property=True), "grid.orc")
    symbolic, _ = _compare(program, program.missions[0])
    assert [o.name for o in symbolic.outcomes if not o.holds] == ["never_lost"]


def test_auto_goes_symbolic_for_robot_tasks_in_parallel():
    program = program_of(_grid()(4, 2), "grid.orc")
    report = check_mission(program, program.missions[0])
    assert report.engine == "symbolic" and "Robot-Tasks in parallel at grid.orc:" in \
        report.engine_reason
    assert report.automaton_states == 82  # 3^4 + 1, the explicit automaton's states
    small = load(ROOT / "missions/arm_pid.orc")
    assert check_mission(small.program, small.program.missions[0]).engine == "explicit"


ESTEREL = sorted((ROOT / "tests/reactive/esterel").glob("*.orc"))


@pytest.mark.parametrize("path", ESTEREL, ids=lambda p: p.stem)
def test_same_built_in_verdicts_on_the_esterel_corpus(path):
    from orccad_app.diagnostics import OrccadError

    source = load(path)
    for mission in source.program.missions:
        try:
            explicit = check_mission(source.program, mission, engine="explicit",
                                     counters=False)
        except OrccadError:
            continue  # refused by the explicit compiler (see the next test for causality)
        symbolic = check_mission(source.program, mission, engine="symbolic")
        assert _verdicts(symbolic) == _verdicts(explicit)


def test_a_non_causal_program_is_refused_by_both_engines_at_the_test():
    from orccad_app.diagnostics import OrccadError

    program = program_of("""
mission Paradox {
    output O;
    signal S { if S { nothing; } else { emit S; } emit O; }
}
""")
    messages = []
    for engine in ("explicit", "symbolic"):
        with pytest.raises(OrccadError) as error:
            check_mission(program, program.missions[0], engine=engine)
        messages.append((str(error.value), error.value.location.line))
    assert all("non-causal" in text for text, _ in messages)
    assert messages[0][1] == messages[1][1] == 4
