"""The last Esterel v5 gaps (issue 28): ``pre(S)`` as a signal expression inside ``and`` /
``or`` conditions and counted triggers, ``pre(S)`` of a local inside ``suspend`` (suspended
instants do not count), and a value read before, in sequence, its emission in the same instant
(non-causal: refused). Modeled on HipHop's Esterel v5 tests (``abortpre``,
``await-count-pre``, ``prepure``); the traces follow Esterel v5's semantics."""

from __future__ import annotations

import pytest

from orccad_app.cli import main
from orccad_app.diagnostics import OrccadError
from tests.reactive.conftest import Run, compile_source, mission


def outputs(decls: str, body: str, script: list[str]) -> list[str]:
    return Run(mission(decls, body), script).outputs


# ------------------------------------------------------------ pre(S) in signal expressions

def test_pre_inside_an_or_and_condition_of_abort():
    # abort when (A or (B and pre(C))): B aborts only one instant after a C
    body = ("abort { loop { emit O; pause; } } when (A or (B and pre(C)));\n"
            "emit Done;")
    decls = "input A, B, C; output O, Done;"
    assert outputs(decls, body, ["", "B", "C", "B"]) == ["O", "O", "O", "Done"]
    assert outputs(decls, body, ["", "C", "", "B"]) == ["O", "O", "O", "O"]  # C too early
    assert outputs(decls, body, ["", "A"]) == ["O", "Done"]


def test_pre_in_a_presence_test_with_not_is_a_rising_edge():
    body = "loop { if (A and not pre(A)) { emit Rise; } pause; }"
    assert outputs("input A; output Rise;", body, ["A", "A", "", "A"]) == \
        ["Rise", "-", "-", "Rise"]


def test_a_counted_trigger_on_pre():
    # HipHop test/await-count-pre.strl: loop { await 3 pre(I); emit O }
    body = "loop { await 3 pre(I); emit O; }"
    assert outputs("input I; output O;", body, ["", "I", "", "I", "I", ""]) == \
        ["-", "-", "-", "-", "-", "O"]


def test_every_on_pre_of_an_output():
    body = "par { loop { await A; emit S; } } || { every (pre(S) or B) { emit O; } }"
    assert outputs("input A, B; output S, O;", body, ["", "A", "", "B"]) == \
        ["-", "S", "O", "O"]


# ------------------------------------------------------------ pre(S) of a local in suspend

SUSPENDED = """suspend {
    signal S {
        loop { if A { emit S; } if pre(S) { emit Was; } pause; }
    }
} when H;"""


def test_pre_of_a_suspended_local_skips_the_suspended_instants():
    # S emitted at instant 1; instants 2 and 3 suspended; at 4 its previous instant is 1
    assert outputs("input A, H; output Was;", SUSPENDED, ["A", "H", "H", "", ""]) == \
        ["-", "-", "-", "Was", "-"]
    # not emitted before the suspension: absent after it
    assert outputs("input A, H; output Was;", SUSPENDED, ["", "A H", "H", ""]) == \
        ["-", "-", "-", "-"]


def test_pre_of_an_interface_signal_counts_every_instant_even_when_suspended():
    body = "suspend { loop { if pre(A) { emit Was; } pause; } } when H;"
    assert outputs("input A, H; output Was;", body, ["A", "H", ""]) == ["-", "-", "-"]


def test_pre_of_a_local_with_suspend_inside_its_scope_counts_every_instant():
    body = ("signal S { par { loop { if A { emit S; } pause; } } || "
            "{ suspend { loop { if pre(S) { emit Was; } pause; } } when H; } }")
    # the scope of S is never suspended: S of instant 2 (suspended reader) is gone at 3
    assert outputs("input A, H; output Was;", body, ["", "A H", "", ""]) == \
        ["-", "-", "Was", "-"]


# ------------------------------------------------------------ values read before emission

def test_a_value_read_in_sequence_before_its_emission_is_refused():
    body = "loop { emit O(?S); if A { emit S(3); } pause; }"
    with pytest.raises(OrccadError, match="non-causal program: [?]S is read here") as \
            caught:
        compile_source(mission("input A; output O : int, S : int := 1;", body))
    assert caught.value.location.line == 3


def test_a_variable_assigned_from_a_value_then_emitted_is_refused():
    body = "var x := ?S; emit S(x + 1); pause;"
    with pytest.raises(OrccadError, match="non-causal"):
        compile_source(mission("output S : int := 0;", body))


def test_a_read_in_parallel_with_the_emission_waits_for_it():
    # Esterel v5 accepts: the read is scheduled after the emission
    body = "loop { par { emit O(?S); } || { if A { emit S(3); } } pause; }"
    assert outputs("input A; output O : int, S : int := 1;", body, ["", "A"]) == \
        ["O(1)", "O(3) S(3)"]


def test_a_read_after_the_emission_and_pre_value_are_accepted():
    body = "loop { if A { emit S(pre(?S) + 1); } emit O(?S); pause; }"
    assert outputs("input A; output O : int, S : int := 0;", body, ["A", "", "A"]) == \
        ["O(1) S(1)", "O(1)", "O(2) S(2)"]


def test_the_command_line_refuses_it_with_a_location_and_exit_2(tmp_path, capsys):
    path = tmp_path / "nc.orc"
    path.write_text(mission("input A; output O : int, S : int := 1;",
                            "loop { emit O(?S); if A { emit S(3); } pause; }"),
                    encoding="utf-8")
    assert main(["compile", str(path)]) == 2
    err = capsys.readouterr().err
    assert f"{path}:3:8: error: non-causal program" in err
