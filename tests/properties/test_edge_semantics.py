"""Signal properties whose arithmetic has no value (issue 28, 6): a division by zero, the
square root of a negative value, an overflow to ±inf give *no verdict, with the reason* — the
run and its report go on (they ended in an internal error or a silently wrong ±inf verdict
labelled "decided by events alone"); a comparison of constants is refused at load."""

from __future__ import annotations

import json
import math

import pytest

from orccad_app.cli import main
from orccad_app.verify import stl_tree as t
from orccad_app.verify.stl import Component, StlFormula, UndefinedRobustness, robustness
from orccad_app.verify.stl_tree import Direction

from tests.properties.test_run_properties import PID, ROOT

EDGES = """
property ArmPID.by_zero: always (1.0 / (arm.q[0] - arm.q[0]) > 0.0);
property ArmPID.sqrt_negative: always (sqrt(0.0 - 1.0 - abs(arm.q[0])) > 0.0);
property ArmPID.overflow: always (arm.q[0] * 1e300 * 1e300 > 0.0);
property ArmPID.fine: always (arm.q[0] < 10.0);
"""


def test_properties_without_a_value_have_no_verdict_and_the_run_keeps_its_report(
        tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(ROOT)
    path = tmp_path / "edges.orc"
    path.write_text(PID + EDGES, encoding="utf-8")
    status = main(["run", str(path), "--until", "0.05", "--json"])
    report = json.loads(capsys.readouterr().out)
    assert status in (0, 1) and report["status"] in ("done", "timeout")
    by_name = {p["name"]: p for p in report["properties"]}
    assert by_name["by_zero"]["verdict"] == "undecided"
    assert by_name["by_zero"]["reason"] == "no robustness on this run: a division by zero"
    assert "square root of a negative value" in by_name["sqrt_negative"]["reason"]
    assert by_name["overflow"]["reason"] == \
        "no robustness on this run: an overflow of its arithmetic to ±inf"
    assert by_name["overflow"]["verdict"] == "undecided"
    assert by_name["fine"]["verdict"] == "true" and "reason" not in by_name["fine"]


def test_a_comparison_of_constants_is_refused_at_load(tmp_path, capsys):
    path = tmp_path / "constants.orc"
    path.write_text(PID + "property ArmPID.constant: always (1.0 < 2.0);\n", encoding="utf-8")
    assert main(["run", str(path), "--until", "0.01"]) == 2
    err = capsys.readouterr().err
    assert "a comparison of constants reads no signal" in err and "constants.orc:" in err


Q0 = {"s0": Component("arm", "q", 0)}


def _below(bound: float, window=None) -> t.Node:
    margin = t.Margin("<", t.Var("s0"), t.Const(bound))
    return margin if window is None else t.Window(window[0], Direction.FUTURE, margin,
                                                  *window[1:])


def test_robustness_raises_for_nan_and_overflow():
    stl = StlFormula(t.Margin(">", t.Arith("-", t.Var("s0"), t.Var("s0")), t.Const(0.0)),
                     Q0, {}, 1_000_000)
    with pytest.raises(UndefinedRobustness, match="not a number"):
        robustness(stl, {"s0": [math.inf, 1.0]})


def test_a_window_past_the_run_stays_vacuously_true_not_an_overflow():
    stl = StlFormula(_below(1.0, ("always", 5 * 10**9, 6 * 10**9)), Q0, {}, 1_000_000_000)
    assert robustness(stl, {"s0": [0.0, 0.0, 0.0]}) == math.inf


ABOVE_0 = t.Margin(">", t.Var("s0"), t.Const(0.0))


@pytest.mark.parametrize("tree, expected", [
    (t.Shift(Direction.FUTURE, ABOVE_0), math.inf),      # no next sample: +inf (weak next)
    (t.Window("eventually", Direction.FUTURE, ABOVE_0, 1_000_000, 2_000_000),
     -math.inf),                                          # no sample in the window
    (t.Window("always", Direction.FUTURE, t.Margin(">", t.Var("s0"), t.Const(0.5))), 0.5),
    (t.Shift(Direction.PAST, ABOVE_0), math.inf),
])
def test_a_one_sample_run_reads_its_only_sample_once(tree, expected):
    # it was read twice: next and windows one period later saw a sample the run did not have
    stl = StlFormula(tree, Q0, {}, 1_000_000)
    assert robustness(stl, {"s0": [1.0]}) == expected


def test_a_window_as_long_as_the_one_year_bound_is_judged_on_the_recorded_part():
    # rtamt's buffers followed the bound: MemoryError, an internal error that lost the report
    year_ns = 365 * 24 * 3600 * 10**9
    stl = StlFormula(_below(10.0, ("always", 0, year_ns)), Q0, {}, 1_000_000)
    assert robustness(stl, {"s0": [1.0, 2.0, 3.0]}) == 7.0
    later = StlFormula(_below(10.0, ("eventually", year_ns // 2, year_ns)), Q0, {}, 1_000_000)
    assert robustness(later, {"s0": [1.0, 2.0, 3.0]}) == -math.inf
