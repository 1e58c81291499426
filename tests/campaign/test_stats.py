"""Statistics as UPPAAL SMC gives them: Clopper-Pearson, Chernoff-Hoeffding, Wald's SPRT."""

from __future__ import annotations

import math

import pytest

from orccad_app.campaign.adapter import RunRecord
from orccad_app.campaign.setting import RunSetting
from orccad_app.campaign.stats import (Hypothesis, Sprt, chernoff_runs, clopper_pearson,
                                       estimates, summarize)
from orccad_app.diagnostics import OrccadError


def _record(index: int, status: str, reason: str | None = None) -> RunRecord:
    outcome = f"{status}({reason})" if reason else status
    return RunRecord(RunSetting(index, index, 10.0), status, reason, outcome, 5.0, 0.1)


def test_clopper_pearson_matches_the_exact_binomial_bounds():
    # k = 0 of 10: the upper bound solves (1 - p)^10 = 0.025
    low, high = clopper_pearson(0, 10, 0.95)
    assert low == 0.0 and high == pytest.approx(1 - 0.025 ** (1 / 10))
    low, high = clopper_pearson(10, 10, 0.95)
    assert high == 1.0 and low == pytest.approx(0.025 ** (1 / 10))
    low, high = clopper_pearson(30, 100, 0.95)  # tabulated: [0.2124, 0.3998]
    assert low == pytest.approx(0.2124, abs=1e-4) and high == pytest.approx(0.3998, abs=1e-4)


def test_the_chernoff_hoeffding_bound_is_uppaals():
    assert chernoff_runs(0.02, 0.95) == math.ceil(math.log(40) / (2 * 0.02 ** 2)) == 4612
    assert chernoff_runs(0.05, 0.99) == 1060


def test_estimates_cover_every_outcome_and_named_exception():
    records = [_record(0, "done"), _record(1, "aborted", "Leak"), _record(2, "done"),
               _record(3, "failed", "BatteryLow")]
    found = estimates(records, 0.95)
    assert found["done"]["count"] == 2 and found["aborted(Leak)"]["count"] == 1
    assert found["failed"]["count"] == 1 and found["timeout"]["count"] == 0
    assert found["failed(BatteryLow)"]["p"] == 0.25


def test_counts_folded_run_by_run_are_the_counts_over_every_run():
    """EventCounts (what a campaign keeps instead of its runs) gives, prefix after prefix,
    every outcome's and property's counts as a count over all the runs, in the same order."""
    import random

    from orccad_app.campaign.adapter import PropertyResult
    from orccad_app.campaign.stats import EventCounts

    draw = random.Random(5)
    counts = EventCounts()
    records = []
    for index in range(40):
        status, reason = draw.choice([("done", None), ("aborted", "Leak"), ("failed", None),
                                      ("failed", "Low"), ("timeout", None)])
        record = _record(index, status, reason)
        for name in draw.sample(["b_prop", "a_prop"], draw.randint(0, 2)):
            record.properties[name] = PropertyResult(draw.choice([True, False, None]), 0.0)
        records.append(record)
        counts.add(record)
        hits, defined = counts.counts()
        statuses = ["done", "failed", "aborted", "recovering", "timeout", "crashed"]
        labels = set(statuses) | {r.outcome for r in records}
        props = sorted({name for r in records for name in r.properties})
        by_status = sorted(labels, key=lambda n: (statuses.index(n.split("(")[0]), n))
        assert list(hits) == by_status + props
        for name in labels:
            assert hits[name] == sum(r.status == name or r.outcome == name for r in records)
            assert defined[name] == len(records)
        for name in props:
            known = [r.properties[name].holds for r in records if name in r.properties
                     and r.properties[name].holds is not None]
            assert (hits[name], defined[name]) == (sum(known), len(known))


def _decide(hypothesis: str, outcomes: list[str]) -> Sprt:
    test = Sprt(Hypothesis.parse(hypothesis), 0.05, 0.05, 0.05)
    for index, status in enumerate(outcomes):
        if test.add(_record(index, status)) is not None:
            break
    return test


def test_sprt_accepts_a_true_hypothesis_and_rejects_a_false_one():
    always = _decide("P(done) >= 0.8", ["done"] * 200)
    assert always.decision is True and always.runs < 60
    never = _decide("P(done) >= 0.8", ["aborted"] * 200)
    assert never.decision is False and never.runs < 10
    at_most = _decide("P(aborted) <= 0.2", ["done"] * 200)
    assert at_most.decision is True
    # inside the indifference region it takes longer to decide
    mixed = _decide("P(done) >= 0.8", (["done"] * 4 + ["aborted"]) * 100)
    assert mixed.runs > always.runs


def test_bad_hypotheses_are_refused():
    with pytest.raises(OrccadError, match="expected 'P"):
        Hypothesis.parse("done > 0.9")
    with pytest.raises(OrccadError, match="indifference region"):
        Sprt(Hypothesis.parse("P(done) >= 0.995"), 0.01, 0.05, 0.05)


def test_summaries_rank_runs_closest_to_violation():
    records = [_record(i, "done") for i in range(5)]
    for record, margin in zip(records, [3.0, -1.0, 2.0, 0.5, 4.0]):
        from orccad_app.campaign.adapter import PropertyResult
        record.properties["p"] = PropertyResult(margin > 0, margin)
    summary = summarize(records, closest=2)
    assert [w["run"] for w in summary["closest_to_violation"]["p"]] == [1, 3]
    assert summary["robustness"]["p"]["min"] == -1.0
    assert summary["completion_time_s"]["n"] == 5
