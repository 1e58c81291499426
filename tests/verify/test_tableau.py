"""The tableau checker against the reference semantics (evaluation on lassos).

For random formulas with every operator, future and past, nested both ways, on the ABRO
model: if some short lasso of the model violates the formula (reference semantics), the
checker finds a counterexample; every counterexample it finds violates the formula.
"""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from orccad_app.verify.checker import check_formula
from orccad_app.verify.formula import (F, TRUE, atom, atoms, conj, disj, neg, nxt, prev,
                                       since, until)
from orccad_app.verify.lasso import holds_on_lasso
from orccad_app.verify.letters import Alphabet

from .conftest import ROOT, holds, model_of

ABRO = model_of((ROOT / "missions" / "abro.orc").read_text())
LEAVES = [atom(("sig", name)) for name in ("A", "B", "R", "O")] + [TRUE]


def formulas():
    return st.recursive(
        st.sampled_from(LEAVES),
        lambda inner: st.one_of(
            inner.map(neg), inner.map(nxt), inner.map(prev),
            inner.map(lambda f: until(TRUE, f)), inner.map(lambda f: neg(until(TRUE, neg(f)))),
            st.tuples(inner, inner).map(lambda p: conj(*p)),
            st.tuples(inner, inner).map(lambda p: disj(*p)),
            st.tuples(inner, inner).map(lambda p: until(*p)),
            st.tuples(inner, inner).map(lambda p: since(*p))),
        max_leaves=5)


def short_lassos(model, alphabet, length):
    """Every lasso of at most ``length`` instants, as (prefix letters, loop letters)."""
    stack = [(0, (), ())]  # state, visited states, letters
    while stack:
        state, visited, letters = stack.pop()
        if len(letters) == length:
            continue
        for step in model.steps[state]:
            for letter, _ in alphabet.letters(step):
                word = letters + (alphabet.letter_set(letter),)
                path = visited + (state,)
                if step.target in path:
                    start = path.index(step.target)
                    yield word[:start], word[start:]
                stack.append((step.target, path, word))


@settings(max_examples=60, deadline=None)
@given(formulas())
def test_checker_agrees_with_the_reference_semantics(f: F):
    lasso, alphabet = check_formula(ABRO, f, fair=False)
    if lasso is not None:
        prefix = [alphabet.letter_set(i.letter) for i in lasso.prefix]
        loop = [alphabet.letter_set(i.letter) for i in lasso.loop]
        assert not holds_on_lasso(f, prefix, loop)
    else:
        alphabet = Alphabet(ABRO, atoms(f))
        for prefix, loop in short_lassos(ABRO, alphabet, 4):
            assert holds_on_lasso(f, prefix, loop), (prefix, loop)


def test_past_over_future_is_supported():
    # once (eventually O) holds everywhere a later O exists: O is reachable from every state
    assert not holds(ABRO, "always once eventually O")
    assert holds(ABRO, "always (O -> once (A and eventually O))")


def test_fairness_of_a_started_task_and_of_timers(tmp_path):
    from .conftest import CORPUS
    text = (CORPUS / "timers.orc").read_text()
    model = model_of(text, "Timers")
    assert holds(model, "eventually Tick")
    lasso, _ = check_formula(model, from_text("eventually Tick"), fair=False)
    assert lasso is not None  # without time divergence the clock may stand still


def from_text(text):
    from .conftest import formula
    return formula(text)


def test_a_widened_periodic_sequence_is_the_same_sequence():
    """Periodic.widened (slices of the prefix and the repeated loop) writes the sequence
    position by position as ``at`` reads it, for prefixes shorter and longer than its own."""
    import random

    from orccad_app.verify.lasso import Periodic

    draw = random.Random(3)
    for _ in range(300):
        sequence = Periodic(tuple(draw.random() < 0.5 for _ in range(draw.randint(0, 5))),
                            tuple(draw.random() < 0.5 for _ in range(draw.randint(1, 4))))
        pre_len = draw.randint(0, 9)
        period = len(sequence.loop) * draw.randint(1, 3)
        wide = sequence.widened(pre_len, period)
        assert wide.pre == tuple(sequence.at(i) for i in range(pre_len))
        assert wide.loop == tuple(sequence.at(pre_len + i) for i in range(period))
