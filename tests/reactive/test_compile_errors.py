"""Programs the compiler must reject, with the location of the fault."""

from __future__ import annotations

import pytest

from orccad_app.diagnostics import OrccadError
from tests.reactive.conftest import compile_source, mission


def reject(decls: str, body: str, **options) -> OrccadError:
    with pytest.raises(OrccadError) as caught:
        compile_source(mission(decls, body), **options)
    return caught.value


def test_present_of_own_negation_is_non_causal():
    error = reject("output O;", "signal S { if S { } else { emit S; } }")
    assert "non-causal" in error.message and "S" in error.message
    assert (error.location.line, error.location.col) == (3, 15)


def test_signal_emitting_itself_is_non_causal():
    error = reject("output O;", "signal S { if S { emit S; } }")
    assert "non-causal" in error.message


def test_cycle_through_two_signals_is_non_causal():
    error = reject("output O;", "signal S, T { par { if S { emit T; } } || { if not T { emit S; } } }")
    assert "non-causal" in error.message


def test_non_causal_only_under_some_input_is_rejected():
    error = reject("input A; output O;", "signal S { await A; if S { } else { emit S; } }")
    assert "non-causal" in error.message


def test_causal_program_with_a_dependency_cycle_in_text_only_is_accepted():
    # S is tested before it is emitted in the text, but nothing depends on itself
    automaton = compile_source(mission("output O;",
                                       "signal S { par { if S { emit O; } } || { emit S; } }"))
    assert automaton.state_count >= 1


def test_instantaneous_loop_is_rejected_at_the_loop():
    error = reject("output O;", "loop { emit O; }")
    assert "instantaneous loop" in error.message
    assert (error.location.line, error.location.col) == (3, 1)


def test_loop_whose_body_may_end_at_once_on_some_path_is_rejected():
    error = reject("input A; output O;", "loop { if A { pause; } }")
    assert "instantaneous loop" in error.message


def test_repeat_of_an_instantaneous_body_is_rejected():
    error = reject("output O;", "repeat 3 { emit O; }")
    assert "repeat" in error.message


def test_state_budget_stops_explosion_with_a_clear_error():
    body = "par " + " || ".join(f"{{ await A{i}; }}" for i in range(8))
    inputs = ", ".join(f"A{i}" for i in range(8))
    error = reject(f"input {inputs}; output O;", body + " emit O;", max_states=50)
    assert "state budget" in error.message and "50" in error.message


def test_undeclared_signal_is_located():
    error = reject("output O;", "await C;")
    assert "undeclared signal 'C'" in error.message
    assert (error.location.line, error.location.col) == (3, 7)


def test_emitting_an_input_is_rejected():
    error = reject("input A;", "emit A;")
    assert "input" in error.message


def test_condition_mixing_presence_and_data_is_rejected():
    error = reject("input A; output O;", "var x := 1; if A and x > 0 { emit O; }")
    assert "mixes" in error.message


def test_value_cycle_is_rejected_at_the_read():
    # the emitted value depends on the read: a real cycle
    error = reject("output V : int;", "signal S : int { emit S(?S + 1); }")
    assert "value of S" in error.message and "non-causal" in error.message
    assert (error.location.line, error.location.col) == (3, 18)


def test_same_program_compiles_to_the_same_automaton():
    from orccad_app.reactive.export import to_json
    source = mission("input A, B, R; output O;",
                     "loop { par { await A; } || { await B; } emit O; halt; } each R;")
    assert to_json(compile_source(source)) == to_json(compile_source(source))


def test_bisimilar_states_are_merged():
    # two awaits of the same signal in parallel behave as one await
    twice = compile_source(mission("input A; output O;", "par { await A; } || { await A; } emit O;"))
    once = compile_source(mission("input A; output O;", "await A; emit O;"))
    assert twice.state_count == once.state_count == 3
