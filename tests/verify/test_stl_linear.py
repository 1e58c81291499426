"""The linear evaluator of signal properties (issue 28, 6) against rtamt, the textbook
implementation it replaced: the same robustness, bit for bit, on random formulas and runs
(bounded and unbounded until/since, windows longer than the run, one-sample runs, events as
±inf), and the sliding-window minimum against its definition."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import HealthCheck, given, settings, strategies as st

from orccad_app.verify import stl_tree as t
from orccad_app.verify.stl_eval import Evaluation, evaluate, sliding
from orccad_app.verify.stl_rtamt import rtamt_robustness
from orccad_app.verify.stl_tree import Direction, UndefinedRobustness

PERIOD_NS = 1_000_000
CHECK = settings(max_examples=300, deadline=None, derandomize=True, database=None,
                 suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])

values = st.floats(-1e3, 1e3, allow_nan=False, allow_infinity=False)
bounds = st.tuples(st.integers(0, 12), st.integers(0, 12)).map(sorted).map(
    lambda ab: (ab[0] * PERIOD_NS, ab[1] * PERIOD_NS))


def terms() -> st.SearchStrategy:
    leaves = st.one_of(st.sampled_from([t.Var("s0"), t.Var("s1")]), values.map(t.Const))
    return st.recursive(leaves, lambda inner: st.one_of(
        st.builds(t.Arith, st.sampled_from("+-*"), inner, inner),
        st.builds(t.Call, st.just("abs"), inner)), max_leaves=4)


def formulas() -> st.SearchStrategy:
    atoms = st.one_of(st.builds(t.Margin, st.sampled_from(["<", "<=", ">", ">="]), terms(),
                                terms()),
                      st.just(t.Event("e0")))
    directions = st.sampled_from(list(Direction))

    def window(op, direction, operand, span):
        return t.Window(op, direction, operand, *(span or (0, None)))

    def until(direction, left, right, span):
        return t.Until(direction, left, right, *(span or (0, None)))

    def compound(inner):
        return st.one_of(
            st.builds(t.Not, inner),
            st.builds(t.Junction, st.sampled_from(["and", "or", "implies"]), inner, inner),
            st.builds(t.Shift, directions, inner),
            st.builds(lambda op, f, span: window(op, Direction.FUTURE, f, span),
                      st.sampled_from(["always", "eventually"]), inner, st.none() | bounds),
            st.builds(lambda op, f, span: window(op, Direction.PAST, f, span),
                      st.sampled_from(["historically", "once"]), inner, st.none() | bounds),
            st.builds(until, directions, inner, inner, st.none() | bounds))
    return st.recursive(atoms, compound, max_leaves=6)


runs = st.integers(1, 16).flatmap(lambda n: st.fixed_dictionaries({
    "s0": st.lists(values, min_size=n, max_size=n),
    "s1": st.lists(values, min_size=n, max_size=n),
    "e0": st.lists(st.sampled_from([math.inf, -math.inf]), min_size=n, max_size=n)}))


def _outcome(function):
    try:
        return function()
    except UndefinedRobustness as undefined:
        return undefined.reason


@CHECK
@given(tree=formulas(), run=runs)
def test_the_linear_evaluator_gives_rtamts_robustness(tree, run):
    arrays = {name: np.asarray(v, dtype=float) for name, v in run.items()}
    ours = _outcome(lambda: evaluate(tree, arrays, PERIOD_NS))
    reference = _outcome(lambda: rtamt_robustness(tree, run, PERIOD_NS))
    assert ours == reference, (tree, run)


simple = st.builds(t.Margin, st.sampled_from(["<", ">"]), st.sampled_from([t.Var("s0"), t.Var("s1")]),
                   values.map(t.Const))


@CHECK
@given(direction=st.sampled_from(list(Direction)), left=simple, right=simple, span=bounds,
       run=runs)
def test_bounded_until_and_since_give_rtamts_robustness(direction, left, right, span, run):
    """The decomposition of the bounded operators, on their own (random formulas above nest
    them, where a wrong window is often masked)."""
    tree = t.Until(direction, left, right, *span)
    arrays = {name: np.asarray(v, dtype=float) for name, v in run.items()}
    if direction is Direction.PAST:  # judge the last sample: it sees the whole past
        tree = t.Window("always", Direction.FUTURE, tree, 0, None)
    assert evaluate(tree, arrays, PERIOD_NS) == rtamt_robustness(tree, run, PERIOD_NS)


def test_bounded_until_and_since_by_hand():
    # left holds on samples 0..2; right first reaches 2.0 at sample 3
    left = [1.0, 1.0, 1.0, -5.0, -5.0]
    right = [-1.0, -1.0, -1.0, 2.0, 3.0]
    run = {"s0": left, "s1": right}
    f = t.Margin(">", t.Var("s0"), t.Const(0.0))
    g = t.Margin(">", t.Var("s1"), t.Const(0.0))
    arrays = {k: np.asarray(v) for k, v in run.items()}
    # window [1, 3]: at k = 3, min(right 2, left over [0, 3) = 1) = 1
    assert evaluate(t.Until(Direction.FUTURE, f, g, PERIOD_NS, 3 * PERIOD_NS), arrays,
                    PERIOD_NS) == 1.0
    # window [0, 2]: right never positive inside: the best is -1
    assert evaluate(t.Until(Direction.FUTURE, f, g, 0, 2 * PERIOD_NS), arrays,
                    PERIOD_NS) == -1.0
    reversed_run = {k: np.asarray(v[::-1]) for k, v in run.items()}
    since = t.Until(Direction.PAST, f, g, PERIOD_NS, 3 * PERIOD_NS)
    # the last sample of the reversed run looks back as the first looked forward
    assert Evaluation(reversed_run, PERIOD_NS).node(since)[-1] == 1.0


@given(values=st.lists(values, min_size=1, max_size=40), width=st.integers(1, 50),
       minimum=st.booleans())
@settings(max_examples=200, deadline=None, derandomize=True, database=None)
def test_the_sliding_window_reduces_each_window(values, width, minimum):
    reduce = min if minimum else max
    expected = [reduce(values[i:i + width]) for i in range(len(values))]
    assert sliding(np.asarray(values), width, minimum).tolist() == expected


def test_undefined_arithmetic_anywhere_in_the_run_has_no_robustness():
    by_zero = t.Window("eventually", Direction.FUTURE, t.Margin(
        ">", t.Arith("/", t.Const(1.0), t.Var("s0")), t.Const(0.0)), 0, PERIOD_NS)
    # the zero is at sample 5, outside the window read at time 0: still no value (rtamt too)
    run = {"s0": [1.0] * 5 + [0.0]}
    arrays = {"s0": np.asarray(run["s0"])}
    assert _outcome(lambda: evaluate(by_zero, arrays, PERIOD_NS)) == "a division by zero"
    assert _outcome(lambda: rtamt_robustness(by_zero, run, PERIOD_NS)) == "a division by zero"
