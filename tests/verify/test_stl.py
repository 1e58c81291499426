"""Signal properties through rtamt against robustness computed by hand, and the LTL runtime
verdicts (true / false / undecided) on finite runs."""

from __future__ import annotations

import math

import pytest

from orccad_app.diagnostics import OrccadError
from orccad_app.lang.parser import parse
from orccad_app.verify.formula import from_ast
from orccad_app.verify.monitor import Verdict, ltl_verdict
from orccad_app.lang.signal_types import PortSignal
from orccad_app.verify.stl import Component, robustness, translate

INF = math.inf
S = 1_000_000_000  # one sample per second
PORTS = {("r", "x"): PortSignal("r", "x", 0, "[m]"),
         ("r", "v"): PortSignal("r", "v", 2, "[m/s]")}


def _rob(text: str, x=(), v=(), events=None, period_ns=S) -> float:
    formula = parse(f"property p: {text};").properties[0].formula
    stl = translate(formula, PORTS, period_ns)
    count = len(x) or len(v) or len(next(iter((events or {}).values())))
    samples = {}
    for name, component in stl.ports.items():
        if component == Component("r", "x"):
            samples[name] = list(x)
        else:
            samples[name] = [vec[component.index] for vec in v]
    for name, key in stl.events.items():
        truth = (events or {}).get(key, [False] * count) if key != ("true",) else [True] * count
        samples[name] = [INF if t else -INF for t in truth]
    return robustness(stl, samples)


def test_always_is_the_worst_margin_in_the_signal_unit():
    assert _rob("always (r.x < 30.0)", x=[10.0, 27.5, 12.0]) == pytest.approx(2.5)
    assert _rob("always (r.x < 30.0)", x=[10.0, 31.0, 12.0]) == pytest.approx(-1.0)
    assert _rob("always (r.x >= 5.0)", x=[10.0, 7.0]) == pytest.approx(2.0)


def test_eventually_is_the_best_margin():
    assert _rob("eventually (r.x > 3.0)", x=[1.0, 4.5, 2.0]) == pytest.approx(1.5)


def test_bounded_eventually_sees_only_its_window():
    # at t=0 the window [1, 2] s holds samples 1 and 2 (values 5, 8): max(5, 8) - 4 = 4
    assert _rob("eventually[1, 2] (r.x > 4.0)", x=[100.0, 5.0, 8.0, 100.0]) == pytest.approx(4.0)
    # always[0, 1]: min over samples 0 and 1 of 10 - x
    assert _rob("always[0 s, 1 s] (r.x < 10.0)", x=[1.0, 7.0, 100.0]) == pytest.approx(3.0)


def test_norm_components_and_arithmetic():
    # norm((3, 4)) = 5: margin 6 - 5 = 1, then 6 - 13 = -7
    assert _rob("always (norm(r.v) < 6.0)", v=[(3.0, 4.0)]) == pytest.approx(1.0)
    assert _rob("always (norm(r.v) < 6.0)", v=[(3.0, 4.0), (5.0, 12.0)]) == pytest.approx(-7.0)
    assert _rob("always (abs(r.v[1] - 2 * r.x) <= 1.0)", x=[1.0], v=[(0.0, 2.5)]) == \
        pytest.approx(0.5)
    assert _rob("always (-r.x / 2 > -3.0)", x=[4.0]) == pytest.approx(1.0)


def test_event_atoms_are_infinite_booleans():
    # the comparison only counts where the event happens
    ended = {("ended", "T"): [False, True, False]}
    assert _rob("always (ended(T) -> r.x < 1.0)", x=[50.0, 0.25, 50.0], events=ended) == \
        pytest.approx(0.75)
    # no comparison decides it: infinite robustness
    assert _rob("always (ended(T) -> eventually done)", events=ended) == -INF
    assert _rob("eventually ended(T)", events=ended) == INF


def test_settles_after_an_event_within_a_bound():
    # ended at t=1; within [0, 2] s after it, |x| falls under 0.5: best margin 0.5 - 0.1
    events = {("ended", "T"): [False, True, False, False, False]}
    x = [9.0, 3.0, 1.0, 0.1, 9.0]
    assert _rob("always (ended(T) -> eventually[0, 2] (abs(r.x) < 0.5))", x=x,
                events=events) == pytest.approx(0.4)
    assert _rob("always (ended(T) -> eventually[0, 1] (abs(r.x) < 0.5))", x=x,
                events=events) == pytest.approx(-0.5)


def test_iff_of_two_events_is_not_nan():
    events = {("sig", "A"): [True, False], ("sig", "B"): [True, False]}
    assert _rob("always (A <-> B)", events=events) == INF


def test_bounds_must_be_multiples_of_the_sampling_period():
    formula = parse("property p: eventually[0, 0.125] (r.x > 1.0);").properties[0].formula
    with pytest.raises(OrccadError, match="not a multiple of the sampling period") as error:
        translate(formula, PORTS, 50_000_000)
    assert error.value.location.col == 23  # the interval


def test_one_sample_is_enough():
    assert _rob("always (r.x < 2.0)", x=[1.5]) == pytest.approx(0.5)


# ---------------------------------------------------------------- LTL verdicts on finite runs

P, Q, NONE = frozenset({("sig", "P")}), frozenset({("sig", "Q")}), frozenset()


def _verdict(text: str, word, ended: bool) -> Verdict:
    return ltl_verdict(from_ast(parse(f"property p: {text};").properties[0].formula), word,
                       ended)


@pytest.mark.parametrize("text, word, ended, expected", [
    ("always P", [P, P], False, Verdict.UNDECIDED),          # the future may break it
    ("always P", [P, NONE], False, Verdict.FALSE),           # broken already
    ("eventually P", [NONE, P], False, Verdict.TRUE),        # seen already
    ("eventually P", [NONE, NONE], False, Verdict.UNDECIDED),
    ("always (P -> once Q)", [Q, P], False, Verdict.TRUE),   # Q seen: holds forever
    ("always (P -> once Q)", [P], False, Verdict.FALSE),
    ("always eventually P", [P], False, Verdict.UNDECIDED),  # never decided by a prefix
    # ended runs stutter forever: decided
    ("eventually P", [NONE, NONE], True, Verdict.FALSE),
    ("always (P -> eventually Q)", [P, Q], True, Verdict.TRUE),
    ("always (P -> eventually Q)", [Q, P], True, Verdict.FALSE),
    ("always not Q", [P, P], True, Verdict.TRUE),
])
def test_ltl_verdicts(text, word, ended, expected):
    assert _verdict(text, word, ended) is expected


@pytest.mark.parametrize("text", ["always P", "eventually P", "always (P -> once Q)",
                                  "always (P -> eventually Q)", "never (P and Q)",
                                  "always eventually P"])
def test_the_running_monitor_gives_the_verdict_of_every_prefix(text):
    """``LtlMonitor`` (the trace's running verdicts) reads each instant once and agrees with
    ``ltl_verdict`` on every prefix of a run, then on the ended run."""
    import random

    from orccad_app.verify.monitor import LtlMonitor

    formula = from_ast(parse(f"property p: {text};").properties[0].formula)
    chooser = random.Random(text)
    for _ in range(4):
        word = [chooser.choice([P, Q, NONE, P | Q]) for _ in range(12)]
        monitor = LtlMonitor(formula)
        for end in range(1, len(word) + 1):
            assert monitor.verdict(word[:end], False) is ltl_verdict(formula, word[:end],
                                                                     False), (word[:end])
        assert monitor.verdict(word, True) is ltl_verdict(formula, word, True)


@pytest.mark.parametrize("text", ["always P", "eventually P", "always (P -> once Q)",
                                  "always (P -> eventually Q)", "P until Q",
                                  "always (P -> next Q)"])
def test_a_verdict_read_past_repeated_letters_is_the_letter_by_letter_one(text):
    """``ltl_verdict`` skips the repeats of a letter that leaves the monitor where it is; on
    words made of runs of one letter it agrees with ``LtlMonitor``, which reads every letter."""
    import random

    from orccad_app.verify.monitor import LtlMonitor

    formula = from_ast(parse(f"property p: {text};").properties[0].formula)
    chooser = random.Random(text)
    for _ in range(6):
        word = [letter for _ in range(5)
                for letter in [chooser.choice([P, Q, NONE, P | Q])] * chooser.randint(1, 6)]
        monitor = LtlMonitor(formula)
        for end in range(1, len(word) + 1):
            assert monitor.verdict(word[:end], False) is ltl_verdict(formula, word[:end],
                                                                     False), (word[:end])


def test_the_model_checker_refuses_a_signal_formula_rather_than_dropping_its_bounds():
    for text in ("always[0, 1] done", "always (done -> r.x < 1.0)"):
        with pytest.raises(OrccadError, match="judged on runs, not by the model checker"):
            from_ast(parse(f"property p: {text};").properties[0].formula)


def test_translated_formulas_give_rtamts_robustness():
    """Formulas of the language, translated (norm, negation, iff, never, bounded until and
    since), evaluated by the linear evaluator and by rtamt on runs of several lengths."""
    from orccad_app.verify.stl_rtamt import rtamt_robustness

    texts = ["always (r.x < 30.0)", "eventually[1, 2] (r.x > 4.0)",
             "always (norm(r.v) < 6.0)", "always[0 s, 1 s] (r.x < 10.0)",
             "(r.x > 3.0) until[1, 3] (r.v[0] > 4.0)", "never[0, 2] (-r.x > 0.0)",
             "always ((r.v[1] > 1.0) since[0, 2] (r.x < 20.0))",
             "(r.x > 8.0) <-> eventually (r.v[0] < 2.0)"]
    runs = [([10.0, 27.5, 12.0], [(3.0, 4.0)] * 3),
            ([100.0, 5.0, 8.0, 100.0, 2.0], [(5.0, 12.0)] * 5),
            ([1.0], [(0.0, 2.5)]), ([31.0, 7.0], [(1.0, 1.0), (8.0, 0.0)])]
    for text in texts:
        stl = translate(parse(f"property p: {text};").properties[0].formula, PORTS, S)
        for x, v in runs:
            samples = {}
            for name, component in stl.ports.items():
                samples[name] = list(x) if component == Component("r", "x") else \
                    [vec[component.index] for vec in v]
            assert robustness(stl, samples) == rtamt_robustness(stl.tree, samples, S), \
                (text, x, v)
