"""The second-wave constructs (issue 11): pre, initial values, combine, counted triggers,
relations, sub-missions and fail, with Esterel v5's meaning where Esterel has them."""

from __future__ import annotations

import subprocess
import sys

import pytest

from orccad_app.reactive.labels import MissionLabel
from orccad_app.diagnostics import OrccadError
from orccad_app.lang.names import check
from orccad_app.lang.parser import parse
from orccad_app.pipeline import ABSTRACT, Source, compile_mission
from orccad_app.reactive.runtime import Reactor, RelationViolation
from tests.reactive.conftest import Run, compile_source, mission


def outputs(decls: str, body: str, script: list[str]) -> list[str]:
    return Run(mission(decls, body), script).outputs


# ---------------------------------------------------------------- pre

def test_pre_is_absent_at_the_first_instant_then_the_previous_status():
    body = "loop { if pre(A) { emit P; } pause; }"
    assert outputs("input A; output P;", body, ["A", "A", "", "A", ""]) == \
        ["-", "P", "P", "-", "P"]


def test_pre_of_a_local_signal_is_absent_in_a_fresh_incarnation():
    # HipHop test/abortpre.hh.js: loop { abort { emit S; pause; emit O } when pre(S); pause }
    body = "loop { abort { emit S; pause; emit O; } when pre(S); pause; }"
    assert outputs("output O, S;", body, ["", "", "", "", ""]) == ["S", "-", "S", "-", "S"]


def test_pre_value_reads_the_end_of_the_previous_instant():
    body = "loop { emit C(pre(?C) + 1); pause; }"
    assert outputs("output C : int := 0;", body, ["", "", ""]) == ["C(1)", "C(2)", "C(3)"]


def test_pre_value_without_initial_value_is_a_located_run_time_error():
    run = Run(mission("output C : int;", "pause; emit C(pre(?C));"), [""])
    with pytest.raises(OrccadError) as caught:
        run.reactor.react(set())
    assert "pre(?C)" in caught.value.message and caught.value.location.line == 3


def test_pre_is_kept_in_the_control_state():
    automaton = compile_source(mission("input A; output P;",
                                       "loop { if pre(A) { emit P; } pause; }"))
    assert automaton.state_count == 2  # after A; after no A (= the first instant)


# ---------------------------------------------------------------- initial values, combine

def test_initial_value_is_read_before_any_emission():
    assert outputs("input Go; output L : float := 1.5, Out : float;",
                   "await Go; emit Out(?L);", ["", "Go"]) == ["-", "Out(1.5)"]


def test_local_signal_initial_value():
    assert outputs("output Out : float;", "signal L : float := 1.5 { emit Out(?L * 2.0); }",
                   [""]) == ["Out(3.0)"]


def test_initial_value_of_the_wrong_type_is_rejected():
    with pytest.raises(OrccadError) as caught:
        compile_source(mission('output L : int := "x";', "nothing;"))
    assert "does not fit" in caught.value.message


@pytest.mark.parametrize("op, values, expected", [
    ("+", (5, 10, 1), 16), ("*", (5, 10, 2), 100), ("min", (5, 10, 2), 2),
    ("max", (5, 10, 2), 10),
])
def test_combine_is_order_independent(op, values, expected):
    for order in (values, tuple(reversed(values))):
        branches = " || ".join(f"{{ emit O({v}); }}" for v in order)
        assert outputs(f"output O : int combine {op};", f"par {branches}", [""]) == \
            [f"O({expected})"]


@pytest.mark.parametrize("op, expected", [("and", "False"), ("or", "True")])
def test_combine_booleans(op, expected):
    body = "par { emit O(true); } || { emit O(false); }"
    assert outputs(f"output O : bool combine {op};", body, [""]) == [f"O({expected})"]


def test_combine_on_a_pure_signal_is_rejected():
    with pytest.raises(OrccadError) as caught:
        compile_source(mission("output O combine +;", "emit O;"))
    assert "combine +" in caught.value.message


# ---------------------------------------------------------------- counted triggers

def test_every_counted():
    assert outputs("input S; output T;", "every 2 S { emit T; }",
                   ["S", "S", "S", "S", "S"]) == ["-", "-", "T", "-", "T"]


def test_abort_counted_is_strong():
    body = "abort { loop { emit W; pause; } } when 2 S; emit Done;"
    assert outputs("input S; output W, Done;", body, ["", "S", "", "S"]) == \
        ["W", "W", "W", "Done"]


def test_weak_abort_counted_lets_the_body_react():
    body = "weak abort { loop { emit W; pause; } } when 2 S do { emit H; }"
    assert outputs("input S; output W, H;", body, ["", "S", "S"]) == ["W", "W", "W H"]


def test_loop_each_counted_restarts_the_body():
    body = "loop { emit Start; halt; } each 2 S;"
    assert outputs("input S; output Start;", body, ["", "S", "S", "S", "S"]) == \
        ["Start", "-", "Start", "-", "Start"]


def test_suspend_counted_is_refused_with_a_reason():
    with pytest.raises(OrccadError) as caught:
        compile_source(mission("input S; output O;", "suspend { emit O; } when 2 S;"))
    assert "cannot be counted" in caught.value.message


# ---------------------------------------------------------------- relations

RELATED = """
input A, B, C;
relation A # B;
relation C => A;
output O;
mission R { loop { if A { emit O; } if B { emit O; } if C { emit O; } pause; } }
"""


def _compiled(text: str, name: str | None = None):
    program = parse(text, "r.orc")
    check(program)
    source = Source("r.orc", text, program)
    chosen = source.program.mission(name) if name else source.program.missions[0]
    return compile_mission(source, chosen, view=ABSTRACT)


def test_relations_prune_transitions():
    related = _compiled(RELATED)
    free = _compiled(RELATED.replace("relation A # B;", "").replace("relation C => A;", ""))
    assert related.transition_count < free.transition_count
    guards = {tuple(sorted((s.name, v) for s, v in t.inputs)) for t in related.transitions()}
    assert all(not (dict(g).get("A") and dict(g).get("B")) for g in guards)
    assert all(not (dict(g).get("C") and dict(g).get("A") is False) for g in guards)


def test_react_rejects_inputs_violating_a_relation():
    reactor = Reactor(_compiled(RELATED))
    reactor.react({"A"})
    with pytest.raises(RelationViolation) as caught:
        reactor.react({"A", "B"})
    assert "A # B" in caught.value.message and caught.value.location.line == 3
    with pytest.raises(RelationViolation):
        reactor.react({"C"})


def test_react_command_locates_the_violating_line(tmp_path):
    path = tmp_path / "r.orc"
    path.write_text(RELATED)
    done = subprocess.run([sys.executable, "-m", "orccad_app.cli", "react", str(path)],
                          input="A\nA B\n", capture_output=True, text=True)
    assert done.returncode == 2
    assert "<stdin>:2:1" in done.stderr and "relation A # B" in done.stderr


def test_relation_over_an_output_is_rejected():
    with pytest.raises(OrccadError) as caught:
        _compiled("input A; output O; mission M { relation A # O; emit O; }")
    assert "not an input" in caught.value.message


# ---------------------------------------------------------------- sub-missions, fail

LIBRARY = """
input Go, Stop;
mission Home [input Start; output Homed] { await Start; emit Homed; }
mission Main {
    output H1, H2, Both;
    run mission Home [Start / Go, Homed / H1];
    run mission Home [Start / Go, Homed / H2];
    emit Both;
}
"""


def test_sub_missions_are_inlined_with_their_signals_renamed():
    reactor = Reactor(_compiled(LIBRARY, "Main"))
    got = [reactor.react(i).outputs for i in ({"Go"}, {"Go"}, set(), {"Go"})]
    assert got == [(), ("H1",), (), ("H2", "Both")]


def test_sub_mission_regions_label_the_states():
    automaton = _compiled(LIBRARY, "Main")
    labels = {label for label in set().union(*automaton.labels)
              if isinstance(label, MissionLabel)}
    assert labels == {MissionLabel("Home", 1), MissionLabel("Home", 2)}


@pytest.mark.parametrize("call, message", [
    ("run mission Nope;", "unknown mission 'Nope'"),
    ("run mission Home [Nope / H1];", "has no signal 'Nope'"),
    ("run mission Home [Start / Go];", "'Homed' is not declared here"),
    ("run mission Home [Start / Go, Homed / V];", "signature mismatch"),
    ("run mission Home [Start / Go, Homed / Stop];", "is an input here"),
])
def test_sub_mission_call_errors(call, message):
    text = LIBRARY.replace("mission Main {", "mission Bad { output H1, V : int; " + call +
                           " }\nmission Main {")
    with pytest.raises(OrccadError) as caught:
        _compiled(text, "Bad")
    assert message in caught.value.message


def test_recursive_sub_missions_are_rejected():
    text = ("mission A [input Go] { await Go; run mission B; }\n"
            "mission B [input Go] { run mission A; }")
    with pytest.raises(OrccadError) as caught:
        _compiled(text, "A")
    assert "recursive sub-mission: A -> B -> A" in caught.value.message


def test_fail_ends_the_mission_failed_and_is_catchable():
    text = """
    input Go, Low;
    output Caught;
    mission F {
        try { await Go; if Low { fail LowBattery; } halt; } catch LowBattery { emit Caught; }
        await Go;
        fail Empty;
    }"""
    reactor = Reactor(_compiled(text))
    reactor.react(set())
    first = reactor.react({"Go", "Low"})
    assert "Caught" in first.outputs and first.status == "running"
    last = reactor.react({"Go"})
    assert (last.status, last.reason) == ("failed", "Empty")
