"""Observation quotients (``orccad check --observe``)."""

from __future__ import annotations

import pytest

from orccad_app.diagnostics import OrccadError
from orccad_app.verify.quotient import format_quotient, observe

from .conftest import CORPUS, ROOT, model_of


def test_the_hand_over_between_two_tasks_is_one_instant():
    model = model_of((CORPUS / "handover.orc").read_text())
    quotient = observe(model, ["Approach.good_end", "Grasp.start", "Grasp.good_end"])
    labels = {(s, " ".join(sorted(l)), t) for s, l, t in quotient.edges}
    start = quotient.initial
    handed = [t for s, l, t in labels if s == start and l == "Approach.good_end Grasp.start"]
    assert len(handed) == 1  # the end of one and the start of the other: the same instant
    assert (handed[0], "Grasp.good_end", next(iter(quotient.ends))) in labels
    assert not any("Grasp.good_end" in l for s, l, t in labels if s == start)


def test_abro_observed_on_o_and_r_has_two_classes():
    model = model_of((ROOT / "missions" / "abro.orc").read_text())
    quotient = observe(model, ["O", "R"])
    assert len(quotient.classes) == 2
    text = format_quotient(quotient, "ABRO")
    assert "class 0 (initial)\n  O -> 1\n  R -> 0" in text


def test_hidden_everything_is_one_class():
    model = model_of((ROOT / "missions" / "abro.orc").read_text())
    assert len(observe(model, ["R"]).classes) == 1


def test_unknown_signal_is_an_error():
    model = model_of((ROOT / "missions" / "abro.orc").read_text())
    with pytest.raises(OrccadError, match="no signal Z"):
        observe(model, ["Z"])
