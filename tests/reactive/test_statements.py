"""Instant-by-instant traces of every reactive statement (Esterel v5 semantics).

Each test compiles a small mission and runs it on an input script; ``outputs[i]`` is what
instant ``i + 1`` emitted (``-`` for nothing).
"""

from __future__ import annotations

from tests.reactive.conftest import mission


def test_nothing_terminates_in_the_first_instant(run):
    r = run(mission("output O;", "nothing; emit O;"), ["", ""])
    assert r.outputs == ["O", "-"]
    assert r.statuses == ["done", "done"]


def test_pause_waits_exactly_one_instant(run):
    r = run(mission("output O, P;", "emit O; pause; emit P;"), ["", "", ""])
    assert r.outputs == ["O", "P", "-"]
    assert r.statuses == ["running", "done", "done"]


def test_halt_never_terminates(run):
    r = run(mission("output O;", "halt; emit O;"), [""] * 4)
    assert r.outputs == ["-"] * 4
    assert set(r.statuses) == {"running"}


def test_valued_emit_carries_its_value(run):
    r = run(mission("output V : float;", "emit V(2.5); pause; emit V(2.5 * 2.0);"), ["", ""])
    assert r.outputs == ["V(2.5)", "V(5.0)"]


def test_sustain_emits_in_every_instant(run):
    r = run(mission("input S; output O;", "abort { sustain O; } when S;"), ["", "", "S", ""])
    assert r.outputs == ["O", "O", "-", "-"]


def test_await_ignores_the_first_instant(run):
    r = run(mission("input A; output O;", "await A; emit O;"), ["A", "", "A", "A"])
    assert r.outputs == ["-", "-", "O", "-"]


def test_await_immediate_sees_the_first_instant(run):
    r = run(mission("input A; output O;", "await immediate A; emit O;"), ["A", "A"])
    assert r.outputs == ["O", "-"]


def test_counted_await_waits_for_the_nth_occurrence(run):
    r = run(mission("input A; output O;", "await 3 A; emit O;"),
            ["A", "A", "", "A", "A", "A"])
    assert r.outputs == ["-", "-", "-", "-", "O", "-"]


def test_await_signal_expressions(run):
    r = run(mission("input A, B; output O, P;",
                    "par { await (A and not B); emit O; } || { await (A or B); emit P; }"),
            ["", "A B", "B", "A"])
    assert r.outputs == ["-", "P", "-", "O"]


def test_await_duration_fires_at_the_first_instant_past_its_deadline(run):
    r = run(mission("output O;", "await 2 s; emit O;"),
            ["@0", "@1.5", "@1.999999999", "@2.5", "@3"])
    assert r.outputs == ["-", "-", "-", "O", "-"]


def test_await_duration_counts_from_the_instant_it_starts(run):
    r = run(mission("input A; output O;", "await A; await 1 s; emit O;"),
            ["@0", "@5 A", "@5.5", "@6"])
    assert r.outputs == ["-", "-", "-", "O"]


def test_if_on_presence(run):
    r = run(mission("input A; output Y, N;",
                    "loop { if A { emit Y; } else { emit N; } pause; }"), ["A", "", "A"])
    assert r.outputs == ["Y", "N", "Y"]


def test_if_on_values_of_a_valued_input(run):
    r = run(mission("input Battery : float; output Low, Ok;",
                    "loop { await Battery; if ?Battery < 20.0 { emit Low; } else { emit Ok; } }"),
            ["", "Battery(50)", "Battery(19.5)", ""])
    assert r.outputs == ["-", "Ok", "Low", "-"]


def test_else_if_chains(run):
    source = mission("input V : int; output A, B, C;",
                     "loop { await V; if ?V > 10 { emit A; } else if ?V > 5 { emit B; } "
                     "else { emit C; } }")
    r = run(source, ["", "V(11)", "V(7)", "V(1)"])
    assert r.outputs == ["-", "A", "B", "C"]


def test_loop_restarts_its_body_in_the_instant_it_terminates(run):
    r = run(mission("output O, P;", "loop { emit O; pause; emit P; }"), ["", "", ""])
    assert r.outputs == ["O", "O P", "O P"]  # declaration order


def test_loop_each_restarts_on_each_occurrence(run):
    r = run(mission("input R; output O;", "loop { emit O; await 2 R; } each R;"),
            ["", "", "R", "", "R"])
    assert r.outputs == ["O", "-", "O", "-", "O"]


def test_repeat_runs_its_body_n_times(run):
    r = run(mission("output O, Done;", "repeat 3 { emit O; pause; } emit Done;"), [""] * 5)
    assert r.outputs == ["O", "O", "O", "Done", "-"]


def test_repeat_zero_times_is_nothing(run):
    r = run(mission("output O, Done;", "repeat 0 { emit O; pause; } emit Done;"), [""])
    assert r.outputs == ["Done"]


def test_every_restarts_the_body_at_each_occurrence(run):
    r = run(mission("input T; output O, P;", "every T { emit O; pause; pause; emit P; }"),
            ["T", "T", "", "T", "", "", "", ""])
    # not in the first instant; restarted at instant 4 before P of the first run
    assert r.outputs == ["-", "O", "-", "O", "-", "P", "-", "-"]


def test_every_duration_is_periodic_from_the_start(run):
    r = run(mission("output Tick;", "every 1 s { emit Tick; }"),
            ["@0", "@0.5", "@1", "@1.2", "@2.5", "@2.7", "@3"])
    assert r.outputs == ["-", "-", "Tick", "-", "Tick", "-", "Tick"]


def test_strong_abort_kills_the_body_without_reacting(run):
    r = run(mission("input S; output O, A;", "abort { loop { emit O; pause; } } when S; emit A;"),
            ["S", "", "S", ""])
    # not in the first instant; at instant 3 the body does not emit O
    assert r.outputs == ["O", "O", "A", "-"]


def test_weak_abort_lets_the_body_react_a_last_time(run):
    r = run(mission("input S; output O, A;",
                    "weak abort { loop { emit O; pause; } } when S; emit A;"), ["", "S"])
    assert r.outputs == ["O", "O A"]


def test_abort_immediate_checks_the_first_instant(run):
    r = run(mission("input S; output O, A;",
                    "abort { emit O; halt; } when immediate S; emit A;"), ["S"])
    assert r.outputs == ["A"]


def test_abort_do_runs_the_handler_only_when_aborted(run):
    source = mission("input S, F; output H, E;",
                     "abort { await F; } when S do { emit H; } emit E;")
    assert run(source, ["", "S", ""]).outputs == ["-", "H E", "-"]
    assert run(source, ["", "F", ""]).outputs == ["-", "E", "-"]


def test_weak_abort_do_when_body_ends_in_the_same_instant_skips_the_handler(run):
    source = mission("input S, F; output H, E;",
                     "weak abort { await F; } when S do { emit H; } emit E;")
    assert run(source, ["", "F S"]).outputs == ["-", "E"]


def test_nested_aborts_outer_wins(run):
    source = mission("input S, T; output I, O, X;",
                     "abort { abort { loop { emit X; pause; } } when T do { emit I; } } "
                     "when S do { emit O; }")
    assert run(source, ["", "S T", ""]).outputs == ["X", "O", "-"]
    assert run(source, ["", "T", "S"]).outputs == ["X", "I", "-"]


def test_suspend_freezes_the_body(run):
    r = run(mission("input S; output O1, O2, O3;",
                    "suspend { emit O1; pause; emit O2; pause; emit O3; } when S;"),
            ["S", "S", "", "S", ""])
    assert r.outputs == ["O1", "-", "O2", "-", "O3"]


def test_suspend_immediate_delays_the_start(run):
    r = run(mission("input S; output O;", "suspend { emit O; } when immediate S;"), ["S", ""])
    assert r.outputs == ["-", "O"]


def test_suspend_of_a_par_freezes_every_branch(run):
    r = run(mission("input S, A; output X, Y;",
                    "suspend { par { loop { emit X; pause; } } || { await A; emit Y; } } when S;"),
            ["", "S A", "A", ""])
    assert r.outputs == ["X", "-", "X Y", "X"]


def test_trap_exit_terminates_the_block(run):
    r = run(mission("output A, B, C;", "trap T { emit A; exit T; emit B; } emit C;"), [""])
    assert r.outputs == ["A C"]


def test_trap_exit_in_par_kills_the_other_branch_after_its_reaction(run):
    r = run(mission("input E; output X, Done;",
                    "trap T { par { loop { emit X; pause; } } || { await E; exit T; } } emit Done;"),
            ["", "E", ""])
    assert r.outputs == ["X", "X Done", "-"]


def test_trap_handle_runs_only_on_exit(run):
    source = mission("input E, F; output H, D;",
                     "trap T { par { await E; exit T; } || { await F; } } handle { emit H; } "
                     "emit D;")
    assert run(source, ["", "E"]).outputs == ["-", "H D"]
    assert run(source, ["", "F", "E"]).outputs == ["-", "-", "H D"]


def test_nested_traps_the_outer_exit_wins(run):
    source = mission("output I, O;",
                     "trap Out { trap In { par { exit In; } || { exit Out; } } handle { emit I; } }"
                     " handle { emit O; }")
    assert run(source, [""]).outputs == ["O"]


def test_par_terminates_when_all_branches_have(run):
    r = run(mission("input A, B; output O;", "par { await A; } || { await B; } emit O;"),
            ["", "A", "", "B"])
    assert r.outputs == ["-", "-", "-", "O"]


def test_race_first_to_end_kills_the_others(run):
    source = mission("input A, B; output WA, WB, End;",
                     "race { await A; emit WA; } || { await B; emit WB; } emit End;")
    assert run(source, ["", "B", "A"]).outputs == ["-", "WB End", "-"]


def test_race_with_simultaneous_ends_runs_both_last_reactions(run):
    source = mission("input A, B; output WA, WB, End;",
                     "race { await A; emit WA; } || { await B; emit WB; } emit End;")
    assert run(source, ["", "A B"]).outputs == ["-", "WA WB End"]


def test_local_signals_are_broadcast_in_the_instant(run):
    r = run(mission("input A; output O;",
                    "signal S { par { await A; emit S; } || { await immediate S; emit O; } }"),
            ["", "A"])
    assert r.outputs == ["-", "O"]


def test_local_signal_fresh_incarnation_in_each_loop_iteration(run):
    # Esterel's schizophrenia example: the S emitted at the end of one iteration is not the S
    # tested by the next iteration in the same instant.
    r = run(mission("output O;", "loop { signal S { if S { emit O; } pause; emit S; } }"),
            ["", "", ""])
    assert r.outputs == ["-", "-", "-"]


def test_valued_local_signal(run):
    r = run(mission("input A; output V : float;",
                    "signal S : float { par { await A; emit S(4.0); } || "
                    "{ await S; emit V(?S + 1.0); } }"), ["", "A"])
    assert r.outputs == ["-", "V(5.0)"]


def test_variables_count_across_instants(run):
    r = run(mission("input A; output N : int;",
                    "var n := 0; loop { await A; n := n + 1; emit N(n); }"),
            ["", "A", "", "A", "A"])
    assert r.outputs == ["-", "N(1)", "-", "N(2)", "N(3)"]


def test_variable_scope_ends_with_its_block(run):
    r = run(mission("output N : int;", "var x := 1; { var x := 5; emit N(x); } pause; emit N(x);"),
            ["", ""])
    assert r.outputs == ["N(5)", "N(1)"]


def test_abro_is_esterels_abro(run):
    with open("missions/abro.orc", encoding="utf-8") as handle:
        source = handle.read()
    r = run(source, ["", "A", "B", "A B", "R", "A B", "R A", "B", "A"])
    assert r.outputs == ["-", "-", "O", "-", "-", "O", "-", "-", "O"]
    assert r.automaton.state_count == 5


def test_if_on_a_boolean_variable_is_a_data_test(run):
    r = run(mission("input A; output Y, N;",
                    "var seen := false; loop { if seen { emit Y; } else { emit N; } "
                    "if A { seen := true; } pause; }"), ["", "A", ""])
    assert r.outputs == ["N", "N", "Y"]
