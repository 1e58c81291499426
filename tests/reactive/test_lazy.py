"""The automaton built on demand (:class:`~orccad_app.reactive.lazy.LazyAutomaton`).

Its agreement with the full automaton on random programs is checked in
:mod:`tests.reactive.test_reference`; here: that it builds only what a run reaches, so a
program far beyond the compiler's state budget runs, that its budgets still fail with a
located message, and that its tree paths are shared by every reactor of the automaton.
"""

from __future__ import annotations

import random

import pytest

from orccad_app.diagnostics import OrccadError
from orccad_app.lang.parser import parse
from orccad_app.reactive.compiler import compile_program
from orccad_app.reactive.lazy import LazyAutomaton
from orccad_app.reactive.lower import lower_mission
from orccad_app.reactive.runtime import Reactor
from tests.reactive.conftest import mission


def par_of_awaits(n: int) -> str:
    """``par { await A1; } || … || { await AN; } emit O;``: 2^N + 1 states."""
    inputs = ", ".join(f"A{i}" for i in range(1, n + 1))
    branches = " || ".join(f"{{ await A{i}; }}" for i in range(1, n + 1))
    return f"mission Par{n} {{\n input {inputs};\n output O;\n par {branches}\n emit O;\n}}\n"


def kernel(source: str):
    program = parse(source, "lazy.orc")
    return lower_mission(program, program.missions[0])


def _run_randomly(automaton, n: int, instants: int) -> int:
    """Runs ``automaton`` (a ParN) on random inputs, a new reactor after each end; the ends."""
    rng = random.Random(n)
    reactor, ends = Reactor(automaton), 0
    for _ in range(instants):
        reaction = reactor.react({f"A{i}" for i in range(1, n + 1) if rng.random() < 0.05})
        if reaction.status == "done":
            assert reaction.outputs == ("O",)
            ends += 1
            reactor = Reactor(automaton)
    return ends


def test_a_program_beyond_the_state_budget_runs_lazily():
    with pytest.raises(OrccadError, match="state budget exceeded"):
        compile_program(kernel(par_of_awaits(11)), max_states=200)
    automaton = LazyAutomaton(kernel(par_of_awaits(11)), max_states=200)
    assert _run_randomly(automaton, 11, 300) >= 1
    assert automaton.state_count < 200


def test_par20_runs():
    automaton = LazyAutomaton(kernel(par_of_awaits(20)))  # 2^20 + 1 states
    assert _run_randomly(automaton, 20, 300) >= 1
    assert automaton.state_count < 300  # the states the runs reached


def test_only_the_taken_path_of_a_tree_is_built():
    automaton = LazyAutomaton(kernel(par_of_awaits(3)))
    reactor = Reactor(automaton)
    reactor.react(set())
    reactor.react({"A1"})
    root = automaton.roots[1]  # the state waiting for A1, A2 and A3
    assert root[1] == "A1" and root[3] is None  # A1 absent: not built
    assert automaton.state_count == 3  # boot, waiting for all, waiting for A2 and A3


def test_reactors_share_what_was_built():
    automaton = LazyAutomaton(kernel(par_of_awaits(4)))
    first = Reactor(automaton)
    for inputs in (set(), {"A1", "A2"}, {"A3", "A4"}):
        first.react(inputs)
    count = automaton.state_count
    second = Reactor(automaton)
    outputs = [second.react(inputs).outputs for inputs in (set(), {"A1", "A2"}, {"A3", "A4"})]
    assert outputs == [(), (), ("O",)]
    assert automaton.state_count == count


def test_the_state_budget_fails_fast_and_located():
    automaton = LazyAutomaton(kernel(par_of_awaits(12)), max_states=5)
    reactor = Reactor(automaton)
    with pytest.raises(OrccadError, match="state budget exceeded") as caught:
        for i in range(1, 13):
            reactor.react({f"A{i}"})
    assert caught.value.location is not None and caught.value.location.file == "lazy.orc"


def test_a_non_causal_instant_is_refused_when_reached_located():
    source = mission("input A; output O, N;",
                     "await A; par { if O { emit N; } } || { if N { } else { emit O; } }")
    automaton = LazyAutomaton(kernel(source))
    reactor = Reactor(automaton)
    reactor.react(set())
    with pytest.raises(OrccadError, match="non-causal") as caught:
        reactor.react({"A"})
    assert caught.value.location.line > 0


def test_waiting_points_and_termination_are_the_full_automatons():
    source = mission("input A, B; output O;", "await A; await B; emit O;")
    full, lazy = Reactor(compile_program(kernel(source))), Reactor(LazyAutomaton(kernel(source)))
    for inputs in (set(), {"B"}, {"A"}, {"A"}, {"B"}):
        assert lazy.react(inputs).outputs == full.react(inputs).outputs
        assert lazy.automaton.waiting[lazy.state] == full.automaton.waiting[full.state]
        assert lazy.finished == full.finished
    assert lazy.finished and lazy.status == "done"
