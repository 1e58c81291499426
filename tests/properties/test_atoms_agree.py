"""A proof and a run read the atoms the same way (issue 24, :mod:`orccad_app.robottask.atoms`).

For every shipped mission, seeded random histories are run on the mission's reactor (what a
run executes) and followed in the checker's model step by step. In each instant the
checker's letter (:class:`~orccad_app.verify.letters.Alphabet`, from the model's step) and
the run monitor's (:func:`~orccad_app.properties.recorder.run_instant`, from the reactor's
inputs, outputs, status and state) must be the same set of atoms — every property's atoms
plus every ``started`` / ``ended`` / ``active`` / ``raised`` / status atom of the mission —
and every LTL property gets the same verdict on both words.
"""

from __future__ import annotations

import random
from pathlib import Path

import pytest

from orccad_app.diagnostics import OrccadError
from orccad_app.lang import ast
from orccad_app.pipeline import load, require_missions
from orccad_app.properties.recorder import run_instant
from orccad_app.reactive.runtime import Reactor
from orccad_app.robottask.atoms import Atoms
from orccad_app.robottask.composition import compose
from orccad_app.robottask.signals import RoleKind
from orccad_app.verify.checker import applicable
from orccad_app.verify.formula import atoms, from_ast
from orccad_app.verify.letters import Alphabet
from orccad_app.verify.model import build_model
from orccad_app.verify.monitor import ltl_verdict

MISSIONS = Path(__file__).resolve().parents[2] / "missions"
HISTORIES = 6
INSTANTS = 60
MODEL_BUDGET = 5000
"""Model states explored with exact counters (beyond, data abstracted: the atoms' meaning does
not depend on it, and AuvWaypoints' exact model takes 20 s)."""
VALUES = {"vector": [15.0, 0.0, 5.0], "float": 1.0, "int": 1, "bool": True}
"""A value for a valued input, by its type."""


def _pairs():
    for path in sorted(MISSIONS.glob("*.orc")):
        source = load(path)
        for mission in source.program.missions:
            yield pytest.param(source, mission, id=mission.name)


def _keys(composition, formulas) -> set[tuple]:
    """The properties' atoms, and every predicate and status atom of the mission."""
    keys: set[tuple] = set()
    for formula in formulas:
        keys |= atoms(formula)
    roles = composition.roles
    tasks = {site.task for site in composition.sites}
    keys |= {(kind, task) for task in tasks for kind in ("started", "ended", "active")}
    keys |= {("raised", name) for name in roles.raised_exceptions()}
    keys |= {("status", status) for status in ("done", "failed", "aborted")}
    keys |= {("sig", s.name) for s in (*composition.automaton.inputs,
                                       *composition.automaton.outputs)}
    return keys


def _model_step(model, state, present, outputs, control):
    """The model's step from ``state`` that the reactor took, or ``None``."""
    for step in model.steps[state]:
        guard = dict(step.path.guard) if step.path is not None else {}
        if any((name in present) != on for name, on in guard.items()):
            continue
        if step.emitted == outputs and model.control(step.target) == control:
            return step
    return None


def _history(composition, model, alphabet, meaning, rng):
    """One random history followed in the model: the two words, and whether it ended."""
    reactor = Reactor(composition.automaton)
    inputs = {s.name: VALUES.get(s.type) if s.type else None
              for s in composition.automaton.inputs}
    state, clock_ns, previous = 0, 0, reactor.status
    checker_word, run_word = [], []
    for _ in range(INSTANTS):
        present = {name for name in inputs if rng.random() < 0.25}
        clock_ns += 10**9 * rng.choice((0, 0, 1, 30)) + 10**6
        try:
            step = reactor.step({name: inputs[name] for name in present}, clock_ns)
        except OrccadError:  # a relation refused the inputs, or a valued input without value
            break
        outputs = frozenset(step.outputs)
        found = _model_step(model, state, present, outputs, reactor.state)
        assert found is not None, f"no model step for inputs {sorted(present)} at {state}"
        guard = dict(found.path.guard) if found.path is not None else {}
        chosen = tuple(n for n in alphabet.inputs if n not in guard and n in present)
        mask = next(m for m, c in alphabet.letters(found) if c == chosen)
        checker_word.append(alphabet.letter_set(mask))
        run_word.append(meaning.letter(run_instant(present | outputs, reactor.status,
                                                   previous, lambda: reactor.labels)))
        previous, state = reactor.status, found.target
        if reactor.finished:
            return checker_word, run_word, True
    return checker_word, run_word, False


@pytest.mark.parametrize("source,mission", list(_pairs()))
def test_checker_and_run_monitor_read_the_same_atoms(source, mission):
    composition = compose(source.program, mission)
    model = build_model(composition, budget=MODEL_BUDGET)
    formulas = {p.name: from_ast(p.formula)
                for p in applicable(source.program.properties, mission)
                if not ast.is_signal_formula(p.formula)}
    keys = _keys(composition, formulas.values())
    alphabet = Alphabet(model, keys)
    meaning = Atoms(composition.roles, keys)
    rng = random.Random(f"{mission.name}-24")
    instants = 0
    seen: set[tuple] = set()
    for _ in range(HISTORIES):
        checker_word, run_word, ended = _history(composition, model, alphabet, meaning, rng)
        for index, (ours, theirs) in enumerate(zip(checker_word, run_word)):
            assert ours == theirs, (f"instant {index}: the checker reads {sorted(ours)}, the "
                                    f"run {sorted(theirs)}")
            seen |= ours
        for name, formula in formulas.items():
            assert ltl_verdict(formula, checker_word, ended) == \
                ltl_verdict(formula, run_word, ended), name
        instants += len(run_word)
    assert instants >= HISTORIES, "the histories stopped at once"
    tasks_started = {key for key in seen if key[0] == "started"}
    assert tasks_started or not composition.sites, "no history started a Robot-Task"


def test_a_predicate_atom_is_its_role_signal():
    """``started(X)`` is X's START signal, found by its role, not by its name."""
    source = load(MISSIONS / "arm_recovery.orc")
    composition = compose(source.program, require_missions(source)[0])
    meaning = Atoms(composition.roles, ())
    task = composition.sites[0].task
    assert meaning.signal(("started", task)) == composition.roles.signal(RoleKind.START, task)
    assert meaning.signal(("started", "NoSuchTask")) is None
