"""A sequential campaign's answer does not depend on which worker was faster (issue 28, 5).

A stand-in backend finishes the runs in a scripted order (no plant: each run's outcome is a
function of its index), so the prefix of finished runs grows by several runs at once; the
campaign must still stop at the smallest ``n`` where its rule holds and compute its statistics
on exactly those ``n`` runs.
"""

from __future__ import annotations

from typing import Any, Iterable

import pytest

from orccad_app.campaign.adapter import RunRecord
from orccad_app.campaign.executor import Job
from orccad_app.campaign.runner import Campaign, CampaignOptions
from orccad_app.campaign.spec import parse_spec
from tests.campaign.conftest import AUV, LEAK_SPEC


class ScriptedBackend:
    """Finishes the flying runs in the batches of ``order`` (indices), then all at once.

    ``outcome(index)`` gives each run's status (``done`` or ``aborted``)."""

    name = "scripted"
    broken = False

    def __init__(self, order: list[set[int]], outcome, workers: int = 2) -> None:
        self.order = list(order)
        self.outcome = outcome
        self.workers = workers
        self.finished: list[int] = []

    def submit(self, job: Job) -> Any:
        return (job.setting.index, job.attempt)

    def wait(self, futures: Iterable[Any]) -> set[Any]:
        flying = set(futures)
        while self.order:
            batch = self.order.pop(0)
            done = {f for f in flying if f[0] in batch}
            if done:
                return done
        return flying

    def result(self, future: Any, job: Job) -> RunRecord:
        self.finished.append(job.setting.index)
        status = self.outcome(job.setting.index)
        return RunRecord(job.setting, status, None if status == "done" else "Leak",
                         "done" if status == "done" else "aborted(Leak)", 1.0, 0.0)

    def restart(self) -> None:
        pass

    def close(self, cancel: bool = False) -> None:
        pass


def _campaign(tmp_path, name: str, **options: Any) -> Campaign:
    spec = parse_spec(LEAK_SPEC, "leak.campaign.toml")
    return Campaign(AUV, spec, CampaignOptions(db=str(tmp_path / f"{name}.db"), **options))


def _every_third_aborted(index: int) -> str:
    return "aborted" if index % 3 == 2 else "done"


@pytest.mark.parametrize("order", [
    [{1, 2}, {0}],               # the prefix jumps from 0 to 3 runs
    [{3, 2, 1}, {0}],            # from 0 to 4
    [{1}, {3}, {2}, {0}],        # one at a time, but run 0 last
])
def test_epsilon_stops_at_the_smallest_n_whatever_the_finishing_order(tmp_path, order):
    # ε = 0.45: two "done" runs already give a half-width <= 0.45 (one run does not)
    options = {"epsilon": 0.45, "workers": 2}
    reference = _campaign(tmp_path, "ref", **options).run(
        backend=ScriptedBackend([], _every_third_aborted, workers=1))
    shuffled = _campaign(tmp_path, "out", **options).run(
        backend=ScriptedBackend(order, _every_third_aborted))
    assert reference.stopped_by == shuffled.stopped_by == "epsilon"
    assert [r.index for r in reference.records] == [0, 1]
    assert [r.index for r in shuffled.records] == [0, 1]
    assert shuffled.estimates == reference.estimates


def test_the_hypothesis_test_stops_at_the_run_that_decides(tmp_path):
    options = {"hypothesis": "P(done) >= 0.5", "delta": 0.2, "workers": 2}
    reference = _campaign(tmp_path, "ref", **options).run(
        backend=ScriptedBackend([], lambda i: "done", workers=1))
    decided = len(reference.records)
    assert reference.stopped_by == "hypothesis" and decided >= 2
    order = [set(range(1, decided + 2)), {0}]  # the prefix jumps past the deciding run
    shuffled = _campaign(tmp_path, "out", **options).run(
        backend=ScriptedBackend(order, lambda i: "done", workers=decided + 2))
    assert [r.index for r in shuffled.records] == list(range(decided))
    assert shuffled.sprt == reference.sprt
