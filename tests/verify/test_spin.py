"""The SPIN cross-check: on a corpus of (mission, property) pairs, holding and failing, our
verdict equals the name's expectation (``holds_*`` / ``fails_*``) and SPIN's verdict on the
Promela export (:mod:`orccad_app.verify.promela`).

Without ``spin`` (Debian package) the SPIN comparison is skipped with the reason, except
under CI (the ``CI`` environment variable set), where ``.ci/run`` installs it: there a
missing ``spin`` fails.
"""

from __future__ import annotations

import os

import pytest

from orccad_app.pipeline import load
from orccad_app.verify.checker import applicable, check_mission
from orccad_app.verify.promela import claim_name, to_promela
from orccad_app.verify.spin import run_spin, spin_available

from .conftest import CORPUS

FILES = sorted(CORPUS.glob("*.orc"))


def _pairs():
    for path in FILES:
        source = load(path)
        for mission in source.program.missions:
            yield source, mission


def _ours(source, mission) -> dict[str, bool]:
    report = check_mission(source.program, mission, builtins=False)
    return {o.name: o.holds for o in report.outcomes}


def test_the_corpus_has_30_pairs_holding_and_failing():
    names = [p.name for source, mission in _pairs()
             for p in applicable(source.program.properties, mission)]
    assert len(names) >= 30
    assert sum(n.startswith("holds_") for n in names) >= 12
    assert sum(n.startswith("fails_") for n in names) >= 12


@pytest.mark.parametrize("source,mission", [pytest.param(s, m, id=m.name) for s, m in _pairs()])
def test_our_verdicts_match_the_corpus(source, mission):
    for name, verdict in _ours(source, mission).items():
        assert verdict == name.startswith("holds_"), f"{mission.name}.{name}"


@pytest.fixture(scope="module")
def spin():
    reason = spin_available()
    if reason is not None:
        if os.environ.get("CI"):
            pytest.fail(f"SPIN cross-check under CI: {reason} (.ci/run installs it)")
        pytest.skip(f"SPIN cross-check skipped: {reason}")
    return run_spin


@pytest.mark.parametrize("source,mission", [pytest.param(s, m, id=m.name) for s, m in _pairs()])
def test_spin_agrees(spin, source, mission):
    properties = applicable(source.program.properties, mission)
    composition = _composition(source, mission)
    text = to_promela(composition.automaton, composition.roles,
                      properties=properties,
                      assumptions=applicable(source.program.assumptions, mission))
    theirs = spin(text, [claim_name(p.name) for p in properties])
    ours = _ours(source, mission)
    assert {p.name: theirs[claim_name(p.name)] for p in properties} == ours


def _composition(source, mission):
    from orccad_app.robottask.composition import compose
    return compose(source.program, mission)
