"""The SCXML export is read back by a real SCXML consumer (python-statemachine) and behaves
like the automaton it came from, instant by instant."""

from __future__ import annotations

import random

import pytest

from orccad_app.reactive.runtime import Reactor
from orccad_app.reactive.scxml import identifier, to_scxml
from tests.reactive.conftest import compile_source, mission

statemachine_io = pytest.importorskip("statemachine.io")


def replay(automaton, instants):
    """Run the automaton and its SCXML side by side; return both traces."""
    chart = statemachine_io.load(to_scxml(automaton), format="scxml")()
    reactor = Reactor(automaton)
    ours, theirs = [], []
    last = {s.name: 0.0 for s in automaton.inputs if s.valued}
    for present, clock_ns in instants:
        reaction = reactor.react(present, clock_ns)
        last.update({k: v for k, v in present.items() if v is not None})
        data = {identifier(s.name): s.name in present for s in automaton.inputs}
        data.update({identifier(n) + "_value": v for n, v in last.items()})
        chart.send("react", clock=reactor.store.clock_ns, **data)
        ours.append((" ".join(reaction.outputs), reaction.status))
        theirs.append((chart.model.emitted, chart.model.status))
    return ours, theirs


def test_abro_scxml_matches_the_automaton():
    with open("missions/abro.orc", encoding="utf-8") as handle:
        automaton = compile_source(handle.read())
    rng = random.Random(7)
    instants = [({n: None for n in "ABR" if rng.random() < 0.4}, None) for _ in range(200)]
    ours, theirs = replay(automaton, instants)
    assert ours == theirs
    assert any(outputs == "O" for outputs, _ in ours)


def test_scxml_with_counters_values_and_timers():
    source = mission("input Pulse, Level : float; output Count : int, High, Tick;",
                     "var n := 0; par { loop { await Pulse; n := n + 1; emit Count(n); } } || "
                     "{ every 1 s { emit Tick; } } || "
                     "{ loop { await Level; if ?Level > 2.5 { emit High; } } }")
    automaton = compile_source(source)
    rng = random.Random(3)
    instants = []
    for i in range(120):
        present = {}
        if rng.random() < 0.3:
            present["Pulse"] = None
        if rng.random() < 0.3:
            present["Level"] = rng.uniform(0.0, 5.0)
        instants.append((present, i * 250_000_000))
    ours, theirs = replay(automaton, instants)
    assert ours == theirs
    assert any("Tick" in o for o, _ in ours) and any("High" in o for o, _ in ours)


def test_composed_arm_mission_scxml_reaches_the_same_statuses():
    from orccad_app.pipeline import compile_mission, load, select_mission
    source = load("missions/arm_pid.orc")
    automaton = compile_mission(source, select_mission(source, None))
    steps = [({}, 0), ({"TrackPID.Saturated": None}, 10**9), ({}, 2 * 10**9), ({}, 4 * 10**9 + 1)]
    ours, theirs = replay(automaton, steps)
    assert ours == theirs and ours[-1][1] == "done"
