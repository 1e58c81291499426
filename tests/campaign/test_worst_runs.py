"""The report's "worst runs" figure shows the worst runs by the score it names (issue 28, 7).

The defect: the axes were the two most influential quantities, an injection's time among them,
and the "worst" were taken among the runs having both axes — the runs with an injection, all
among the best — under a "worst 10 %" label.
"""

from __future__ import annotations

import pytest

from orccad_app.campaign.adapter import PropertyResult, RunRecord
from orccad_app.campaign.report import figures, worst_runs
from orccad_app.campaign.runner import CampaignResult
from orccad_app.campaign.setting import RunSetting
from orccad_app.campaign.stats import estimates, summarize

pytest.importorskip("matplotlib")


def _record(index: int) -> RunRecord:
    injected = index % 4 == 0
    values = {"a": float(index % 7), "b": float((index * 3) % 11),
              "inject[0].occurs": float(injected)}
    if injected:  # the injected runs are all among the best, their robustness set by the time
        values["inject[0].time_s"] = 10.0 + index
        robustness = 100.0 + index
    else:
        robustness = float(index % 7) - 3.0 + 0.01 * index
    setting = RunSetting(index, index, 30.0, values=values)
    return RunRecord(setting, "done", None, "done", 1.0, 0.0,
                     properties={"p": PropertyResult(robustness >= 0, robustness)})


def test_the_figure_plots_the_worst_runs_by_its_score() -> None:
    records = [_record(i) for i in range(60)]
    result = CampaignResult("f.orc", "M", records, estimates(records, 0.95),
                            summarize(records), "runs", 0.95)
    axes = figures(result)["worst_runs"].axes[0]
    score = {r.index: r.properties["p"].robustness for r in records}
    expected = worst_runs(records, score)
    assert max(score[r.index] for r in expected) < 0  # the worst are the violating runs
    highlighted = axes.collections[1]
    assert sorted(highlighted.get_array()) == sorted(score[r.index] for r in expected)
    for label in (axes.get_xlabel(), axes.get_ylabel()):
        assert not label.startswith("inject[0].time_s")
    legend = [t.get_text() for t in axes.get_legend().get_texts()]
    assert legend == ["all 60 runs", f"the {len(expected)} worst by robustness of p"]
