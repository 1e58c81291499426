"""The summary, the strict JSON and the progress bar of a campaign, on synthetic runs."""

from __future__ import annotations

import json

from orccad_app.campaign.adapter import PropertyResult, RunRecord
from orccad_app.campaign.output import Progress, format_result, result_dict
from orccad_app.campaign.runner import CampaignResult, PrefixCounts
from orccad_app.campaign.setting import RunSetting
from orccad_app.campaign.stats import estimates, summarize


def _result() -> CampaignResult:
    records = []
    for index, (status, reason, margin) in enumerate(
            [("done", None, 2.0), ("aborted", "Leak", float("inf")), ("done", None, -0.5)]):
        outcome = f"{status}({reason})" if reason else status
        record = RunRecord(RunSetting(index, 7 + index, 100.0, values={"x": float(index)}),
                           status, reason, outcome, 50.0 + index, 0.2,
                           {"max(auv.depth)": 10.0 + index, "completion_time_s": None})
        record.properties["safe_depth"] = PropertyResult(margin > 0, margin)
        records.append(record)
    return CampaignResult("m.orc", "M", records, estimates(records, 0.95), summarize(records),
                          "runs", 0.95, {1: "orccad run m.orc --seed 8"}, db="c.db")


def test_json_is_strict_and_complete():
    text = json.dumps(result_dict(_result()), allow_nan=False)
    data = json.loads(text, parse_constant=lambda c: (_ for _ in ()).throw(ValueError(c)))
    assert data["estimates"]["aborted(Leak)"]["count"] == 1
    assert data["results"][1]["properties"]["safe_depth"]["robustness"] is None  # +inf
    assert data["replay"] == {"1": "orccad run m.orc --seed 8"}


def test_the_summary_names_probabilities_distributions_and_replays():
    text = format_result(_result())
    assert "aborted(Leak)" in text and "Clopper-Pearson" in text
    assert "robustness safe_depth" in text and "max(auv.depth)" in text
    assert "run    1  aborted(Leak):  orccad run m.orc --seed 8" in text


def test_the_progress_bar_shows_the_running_estimate():
    progress = Progress(0.95)
    prefix = PrefixCounts()
    for record in _result().records[:2]:
        prefix.add(record)
    progress(2, 3, prefix)
    task = progress.bar.tasks[0]
    assert (task.completed, task.total) == (2, 3)
    assert task.fields["estimate"].startswith("P(done) = 0.500 [")
