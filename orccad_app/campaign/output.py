"""A campaign's result for people (a summary table) and for programs (strict JSON), and the
live progress bar (rich, on a terminal only)."""

from __future__ import annotations

from typing import Any

from orccad_app.campaign.runner import CampaignResult, PrefixCounts
from orccad_app.jsonout import plain
from orccad_app.reactive.status import MissionStatus

__all__ = ["result_dict", "format_result", "Progress"]


def result_dict(result: CampaignResult) -> dict[str, Any]:
    """The ``--json`` object (docs/campaigns.md)."""
    runs = []
    for record in result.records:
        runs.append({"run": record.index, "seed": record.setting.seed,
                     "status": record.status, "outcome": record.outcome,
                     "reason": record.reason, "sim_time_s": record.sim_time_s,
                     "attempts": record.attempts, "metrics": record.metrics,
                     "properties": {k: {"holds": p.holds, "robustness": p.robustness}
                                    for k, p in record.properties.items()},
                     "setting": record.setting.as_dict()})
    return plain({"file": result.file, "mission": result.mission, "runs": len(result.records),
                   "backend": result.backend, "stopped_by": result.stopped_by,
                   "interrupted": result.interrupted, "confidence": result.confidence,
                   "wall_time_s": result.wall_time_s, "database": result.db,
                   "estimates": result.estimates, "hypothesis": result.sprt,
                   "distributions": result.summary,
                   "replay": {str(k): v for k, v in sorted(result.replays.items())},
                   "results": runs})


def _num(value: Any, digits: int = 4) -> str:
    if value is None:
        return "-"
    return f"{value:.{digits}g}"


def format_result(result: CampaignResult) -> str:
    """The summary printed at the end of a campaign."""
    level = f"{100 * result.confidence:g} %"
    lines = [f"Campaign {result.mission} ({result.file}): {len(result.records)} runs on "
             f"{result.backend}, {result.wall_time_s:.1f} s; stopped by: {result.stopped_by}",
             "", f"{'event':<34} {'count':>11} {'P':>7}  {level} Clopper-Pearson interval"]
    for name, e in result.estimates.items():
        if not e["runs"]:
            continue
        lines.append(f"{name:<34} {e['count']:>5}/{e['runs']:<5} {_num(e['p'], 3):>7}  "
                     f"[{e['low']:.3f}, {e['high']:.3f}]")
    if result.sprt is not None:
        s = result.sprt
        lines += ["", f"Hypothesis {s['hypothesis']} (SPRT, indifference ±{s['delta']:g}, "
                      f"α = β = {s['alpha']:.3g}): {s['decision'] or 'undecided'} after "
                      f"{s['runs']} runs"]
    summary = result.summary
    lines += ["", f"{'distribution':<34} {'n':>5} {'min':>9} {'median':>9} {'mean':>9} "
                  f"{'max':>9}"]
    rows = [("completion time [s]", summary["completion_time_s"])]
    rows += [(f"robustness {k}", v) for k, v in summary["robustness"].items()]
    rows += [(k, v) for k, v in summary["metrics"].items()
             if k.startswith(("max(", "min(")) or ".tracking_error." in k]
    for name, d in rows:
        if d is not None:
            lines.append(f"{name:<34} {d['n']:>5} {_num(d['min']):>9} {_num(d['median']):>9} "
                         f"{_num(d['mean']):>9} {_num(d['max']):>9}")
    for prop, worst in summary["closest_to_violation"].items():
        if worst:
            lines += ["", f"Closest to violation of {prop}:"]
            lines += [f"  run {w['run']:>4}  robustness {_num(w['robustness'])}:  "
                      f"{result.replays.get(w['run'], '')}" for w in worst]
    failing = [r for r in result.records if r.status != MissionStatus.DONE][:5]
    if failing:
        lines += ["", "Replay (first runs not done):"]
        lines += [f"  run {r.index:>4}  {r.outcome}:  {result.replays.get(r.index, '')}"
                  for r in failing]
    lines += ["", f"Database: {result.db}"]
    return "\n".join(lines)


class Progress:
    """A rich progress bar with ETA and the running ``P(done)`` (terminal only)."""

    def __init__(self, confidence: float) -> None:
        from rich.progress import (BarColumn, MofNCompleteColumn, Progress as Bar,
                                   TextColumn, TimeRemainingColumn)

        self.confidence = confidence
        self.bar = Bar(TextColumn("campaign"), BarColumn(), MofNCompleteColumn(),
                       TimeRemainingColumn(), TextColumn("{task.fields[estimate]}"),
                       transient=True)
        self.task = self.bar.add_task("runs", total=None, estimate="")
        self._shown: tuple[int, int] | None = None  # (prefix runs, of which done) shown
        self._text = ""

    def __enter__(self) -> Progress:
        self.bar.__enter__()
        return self

    def __exit__(self, *exc: Any) -> None:
        self.bar.__exit__(*exc)

    def __call__(self, done: int, limit: int, prefix: PrefixCounts) -> None:
        from orccad_app.campaign.stats import clopper_pearson

        counted = (prefix.length, prefix.done)
        if counted != self._shown and prefix.length:
            self._shown = counted
            low, high = clopper_pearson(prefix.done, prefix.length, self.confidence)
            self._text = (f"P(done) = {prefix.done / prefix.length:.3f} "
                          f"[{low:.3f}, {high:.3f}]")
        self.bar.update(self.task, completed=done, total=limit, estimate=self._text)
