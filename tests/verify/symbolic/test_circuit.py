"""The circuit is the engine's instant: every explicit transition of every shipped mission,
of the verification corpus, of the Esterel corpus and of random programs, equal."""

from __future__ import annotations

from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings

from orccad_app.diagnostics import OrccadError
from orccad_app.pipeline import compose, load
from orccad_app.reactive.prepare import prepare
from tests.reactive.strategies import expand, programs
from tests.verify.symbolic.differential import mismatches

ROOT = Path(__file__).resolve().parents[3]
FILES = sorted([*ROOT.glob("missions/*.orc"), *ROOT.glob("missions/lib/*.orc"),
                *ROOT.glob("tests/verify/corpus/*.orc")])


@pytest.mark.parametrize("path", FILES, ids=lambda p: str(p.relative_to(ROOT)))
def test_every_transition_of_the_composed_missions(path):
    source = load(path)
    for mission in source.program.missions:
        prep = compose(source.program, mission, lazy=True).automaton.prep
        compared, found = mismatches(prep)
        assert compared > 0
        assert not found, found[:3]


ESTEREL = sorted((ROOT / "tests/reactive/esterel").glob("*.orc"))


@pytest.mark.parametrize("path", ESTEREL, ids=lambda p: p.stem)
def test_the_esterel_corpus(path):
    from orccad_app.reactive.lower import lower_mission

    try:
        source = load(path)
        kernels = [lower_mission(source.program, m) for m in source.program.missions]
        preps = [prepare(k) for k in kernels]
        for prep in preps:
            mismatches(prep)  # the explicit compile first: a refused program is skipped
    except OrccadError:
        pytest.skip("the explicit compiler refuses this program")
    for prep in preps:
        compared, found = mismatches(prep)
        assert not found, found[:3]


@settings(max_examples=60, deadline=None, suppress_health_check=list(HealthCheck))
@given(programs())
def test_random_programs(program):
    try:
        prep = prepare(expand(program))
        compared, found = mismatches(prep)
    except OrccadError:
        return  # refused by the explicit compiler (causality, budget): nothing to compare
    assert not found, found[:3]
