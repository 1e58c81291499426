"""Signal values with Esterel v5's meaning (issue 11, defects 1-3).

A read of ``?S`` is performed after every emission of S of the instant, whatever parallel
branch holds it; a local signal declared in a loop is a fresh signal at each iteration; two
emissions of a valued signal in one instant need ``combine``.
"""

from __future__ import annotations

import pytest

from orccad_app.diagnostics import OrccadError
from tests.reactive.conftest import Run, compile_source, mission


def outputs(decls: str, body: str, script: list[str]) -> list[str]:
    return Run(mission(decls, body), script).outputs


# ---------------------------------------------------------------- defect 1: branch order

@pytest.mark.parametrize("body", [
    "signal I : int { par { emit J(?I); } || { emit I(5); } }",
    "signal I : int { par { emit I(5); } || { emit J(?I); } }",
    "signal I : int { par { await immediate I; emit J(?I); } || { emit I(5); } }",
    "signal I : int { par { emit I(5); } || { await immediate I; emit J(?I); } }",
])
def test_a_read_waits_for_the_emission_whatever_the_branch_order(body):
    assert outputs("output J : int;", body, [""]) == ["J(5)"]


@pytest.mark.parametrize("swap", [False, True])
def test_a_value_test_waits_for_the_other_branch(swap):
    reader = "{ loop { if ?B > 3 { emit A; } pause; } }"
    writer = "{ loop { if C { emit B(4); } else { emit B(3); } pause; } }"
    branches = (writer, reader) if swap else (reader, writer)
    body = f"par {branches[0]} || {branches[1]}"
    got = outputs("input C; output A, B : int;", body, ["", "", "C", "", "C"])
    assert got == ["B(3)", "B(3)", "A B(4)", "B(3)", "A B(4)"]


# ---------------------------------------------------------------- defect 2: fresh locals

def test_a_local_signal_declared_in_a_loop_is_fresh_at_each_iteration():
    body = "loop { signal L : int { emit L(4); pause; emit S(?L + 5); } }"
    assert outputs("output S : int;", body, ["", "", "", ""]) == ["-", "S(9)", "S(9)", "S(9)"]


def test_the_old_incarnation_keeps_its_value():
    # each iteration emits a new value; the read sees the one of its own incarnation
    body = ("var n := 0; loop { n := n + 1; signal L : int { emit L(n); pause; "
            "emit S(?L * 10); } }")
    assert outputs("output S : int;", body, ["", "", "", ""]) == ["-", "S(10)", "S(20)", "S(30)"]


def test_an_output_read_before_its_emission_after_the_loop_restarts_is_refused():
    # the read comes, in sequence, before the next iteration's emission of the same output:
    # Esterel v5 rejects it as non-constructive, ORCCAD as non-causal (issue 28); a local
    # is fresh instead (above)
    body = "loop { emit L(4); pause; emit S(?L + 5); }"
    with pytest.raises(OrccadError, match="non-causal program: [?]L is read here"):
        compile_source(mission("output L : int, S : int;", body))


# ---------------------------------------------------------------- defect 3: two emissions

@pytest.mark.parametrize("body", [
    "par { emit O(5); } || { emit O(10); }",
    "par { emit O(10); } || { emit O(5); }",
])
def test_two_emissions_without_combine_are_a_located_compile_error(body):
    with pytest.raises(OrccadError) as caught:
        compile_source(mission("output O : int;", body))
    assert "emitted twice" in caught.value.message and "combine" in caught.value.message
    assert caught.value.location.line == 3


def test_two_emissions_the_compiler_cannot_rule_out_fail_at_run_time():
    body = ("var x := 0; loop { await A; x := x + 1; "
            "par { if x > 1 { emit O(1); } } || { if x > 2 { emit O(2); } } }")
    run = Run(mission("input A; output O : int;", body), ["A", "A"])
    assert run.outputs == ["-", "-"]
    with pytest.raises(OrccadError) as caught:
        run.reactor.react({"A"})  # x = 1: no emission
        run.reactor.react({"A"})  # x = 2: O(1)
        run.reactor.react({"A"})  # x = 3: both
    assert "emitted twice" in caught.value.message
    assert caught.value.location.line == 3


# ------------------------------------------ issue 34 item 14: pre(?S) of a fresh local

_PRE_TEST = """\
loop {
    signal Internal : int := -1 {
        abort {
            loop {
                if pre(?Internal) == -1 { emit O(1); } else { emit O(2); }
                if A { emit Internal(5); }
                pause;
            }
        } when R;
    }
}"""


def _lazy_outputs(source: str, script: list[str]) -> list[str]:
    from orccad_app.lang.parser import parse
    from orccad_app.reactive.lazy import LazyAutomaton
    from orccad_app.reactive.lower import lower_mission
    from orccad_app.reactive.runtime import Reactor
    from orccad_app.reactive.script import parse_script

    program = parse(source, "test.orc")
    automaton = LazyAutomaton(lower_mission(program, program.missions[0]))
    reactor = Reactor(automaton)
    got = []
    for instant in parse_script("\n".join(script) + "\n", "s.in", automaton.inputs):
        reaction = reactor.react(instant.inputs, instant.time_ns)
        got.append(" ".join(f"{o}({reaction.values[o]})" for o in reaction.outputs) or "-")
    return got


def test_pre_of_a_local_in_a_data_test_is_its_initial_value_in_its_first_instant():
    # HipHop's preval and docs/language.md: pre(?S) is S's initial value in the first instant
    # of its incarnation; it was a run-time error ("read before Internal ever had a value")
    # at the first instant, and the old incarnation's last value after a restart
    source = mission("input A, R; output O : int;", _PRE_TEST)
    script = ["A", "", "R", "", "A", "", "R", ""]
    expected = ["O(1)", "O(2)", "O(1)", "O(1)", "O(1)", "O(2)", "O(1)", "O(1)"]
    assert outputs("input A, R; output O : int;", _PRE_TEST, script) == expected
    assert _lazy_outputs(source, script) == expected
    # in an emission it was already the initial value: both reads agree
    emitted = _PRE_TEST.replace(
        "if pre(?Internal) == -1 { emit O(1); } else { emit O(2); }", "emit O(pre(?Internal));")
    assert outputs("input A, R; output O : int;", emitted, script) == \
        ["O(-1)", "O(5)", "O(-1)", "O(-1)", "O(-1)", "O(5)", "O(-1)", "O(-1)"]


def test_pre_of_a_local_without_initial_value_in_a_first_instant_test_is_a_located_error():
    body = ("signal Internal : int { loop { if pre(?Internal) == -1 { emit O(1); } "
            "pause; } }")
    with pytest.raises(OrccadError, match="first instant of local signal Internal, which has "
                                          "no initial value"):
        outputs("output O : int;", body, [""])
