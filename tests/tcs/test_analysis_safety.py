"""The timing analysis against the executive, on seeded random task sets.

For each of the 8 protocols, generated sets (tests/tcs/random_sets.py: 2–5 Module-Tasks on
1–3 processors, harmonic and coprime periods, utilizations up to about 1, offsets, short
deadlines, context switches, bus transfer times) are analysed and run under fixed priority and
EDF. The property: when ``analyse_timing`` says schedulable, the run has no deadline miss and
no overrun (the bound is safe). The pessimism — clean runs the analysis rejects — is measured;
docs/executive.md reports it from the larger surveys of ``python -m tests.tcs.random_sets``
(1200 sets per protocol; 200 sets run for 400 ms each with ``--horizon-ms 400``), which exit
with status 1 when a set is unsafe.
"""

from __future__ import annotations

import pytest

from orccad_app.tcs.protocol import Protocol
from tests.tcs.random_sets import survey, table

SETS_PER_PROTOCOL = 32
"""8 protocols x 32 sets = 256 sets, each run under FP and EDF (a few seconds)."""


@pytest.fixture(scope="module")
def outcome():
    return survey(SETS_PER_PROTOCOL)


def test_at_least_200_sets_are_analysed_and_run(outcome):
    sets = sum(c["runs"] for (_, scheduler), c in outcome.counts.items() if scheduler == "fp")
    assert sets >= 200


def test_schedulable_implies_no_miss_in_the_run(outcome):
    assert outcome.unsafe_cases == []


@pytest.mark.parametrize("protocol", [p.value for p in Protocol])
@pytest.mark.parametrize("scheduler", ["fp", "edf"])
def test_every_protocol_and_scheduler_has_both_verdicts(outcome, protocol, scheduler):
    counts = outcome.counts[(protocol, scheduler)]
    assert counts["said_ok"] >= 2, "the analysis accepts some sets"
    assert counts["runs"] - counts["clean"] >= 2, "some runs miss: the property has teeth"


def test_pessimism_stays_bounded(outcome):
    clean = sum(c["clean"] for c in outcome.counts.values())
    rejected = sum(c["pessimistic"] for c in outcome.counts.values())
    assert rejected / clean < 0.5, table(outcome)


@pytest.fixture(scope="module")
def sporadic_outcome():
    return survey(SPORADIC_SETS_PER_PROTOCOL, first_seed=50_000, sporadic=True)


SPORADIC_SETS_PER_PROTOCOL = 16
"""The same sets with one or two sporadic Module-Tasks each (8 x 16 sets, FP and EDF)."""


def test_schedulable_implies_no_miss_with_sporadic_module_tasks(sporadic_outcome):
    # a sporadic Module-Task is analysed as periodic with its minimum inter-arrival time;
    # the executive releases it on its inputs' writes and external interrupts, deferring
    # those that come too early, so the analysis stays safe
    assert sporadic_outcome.unsafe_cases == []
    counts = sporadic_outcome.counts.values()
    assert sum(c["said_ok"] for c in counts) >= 20, "the analysis accepts some sets"
    assert sum(c["runs"] - c["clean"] for c in counts) >= 20, "some runs miss"
    assert sum(c["deferred"] for c in counts) > 1000, "early interrupts were deferred"
