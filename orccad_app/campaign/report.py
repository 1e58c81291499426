"""The campaign report: ``--report OUT.html`` (one self-contained file) or ``--report DIR``
(PNG figures and ``report.md``).

Figures (matplotlib, drawn off-screen with the Agg backend: static images that embed in one
HTML file and in Markdown, with no JavaScript or server — plotly's interactivity is not worth
a browser runtime for five figures, and matplotlib already draws the docs' plots):

1. outcome and property probabilities as bars with their Clopper–Pearson intervals;
2. each property's robustness histogram (0 marked: left of it, violated);
3. the completion time of the runs that ended ``done``;
4. the worst tenth of the runs (at least five) by the score it names — the robustness of the
   property most at risk (most violations, then the smallest robustness), or ``done`` when no
   property has a robustness — over the two drawn quantities every run has that influence the
   score most (|Spearman ρ|);
5. the replay commands of the worst runs and of the runs that did not end ``done``.
"""

from __future__ import annotations

import base64
import html
import io
from pathlib import Path
from typing import Any

from orccad_app.campaign.runner import CampaignResult
from orccad_app.campaign.stats import influence
from orccad_app.diagnostics import OrccadError
from orccad_app.reactive.status import MissionStatus

__all__ = ["write_report", "figures", "worst_runs"]


def _pyplot() -> Any:
    try:
        import matplotlib
    except ImportError:
        raise OrccadError("--report needs matplotlib: pip install 'orccad[report]'") from None
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


_ALWAYS_SHOWN = frozenset(MissionStatus) - {MissionStatus.RECOVERING}
"""The outcomes drawn even when no run had them."""


def _outcomes(plt: Any, result: CampaignResult) -> Any:
    shown = [(k, e) for k, e in result.estimates.items() if e["runs"] and
             (e["count"] or k in _ALWAYS_SHOWN)]
    fig, ax = plt.subplots(figsize=(7, 0.45 * len(shown) + 1.2))
    names = [k for k, _ in shown]
    p = [e["p"] for _, e in shown]
    low = [e["p"] - e["low"] for _, e in shown]
    high = [e["high"] - e["p"] for _, e in shown]
    ax.barh(names, p, xerr=[low, high], color="#4c72b0", capsize=3)
    ax.invert_yaxis()
    ax.set_xlim(0, 1)
    ax.set_xlabel(f"probability ({100 * result.confidence:g} % Clopper–Pearson interval)")
    ax.set_title(f"{result.mission}: {len(result.records)} runs")
    fig.tight_layout()
    return fig


def _robustness(plt: Any, result: CampaignResult) -> Any | None:
    props = [k for k, v in result.summary["robustness"].items() if v]
    if not props:
        return None
    fig, axes = plt.subplots(1, len(props), figsize=(4 * len(props), 3), squeeze=False)
    for ax, name in zip(axes[0], props):
        values = [r.properties[name].robustness for r in result.records
                  if name in r.properties and r.properties[name].robustness is not None]
        ax.hist(values, bins=20, color="#55a868")
        ax.axvline(0.0, color="#c44e52")
        ax.set_title(f"robustness of {name}")
        ax.set_xlabel("margin to violation (signal unit)")
    fig.tight_layout()
    return fig


def _completion(plt: Any, result: CampaignResult) -> Any | None:
    times = [r.sim_time_s for r in result.records if r.status == MissionStatus.DONE]
    if not times:
        return None
    fig, ax = plt.subplots(figsize=(6, 3))
    ax.hist(times, bins=20, color="#8172b2")
    ax.set_xlabel("completion time [s] (runs ending done)")
    ax.set_ylabel("runs")
    fig.tight_layout()
    return fig


def _score(result: CampaignResult) -> tuple[str, dict[int, float]]:
    """The robustness of the property most at risk (most violations, then the smallest
    robustness), or ``done`` when no property has a robustness."""
    props = [k for k, v in result.summary["robustness"].items() if v]
    if props:
        name = min(props, key=lambda k: (-(result.estimates[k]["runs"]
                                           - result.estimates[k]["count"]),
                                         result.summary["robustness"][k]["min"]))
        return f"robustness of {name}", {
            r.index: value for r in result.records if name in r.properties
            if (value := r.properties[name].robustness) is not None}
    return "done (1) or not (0)", {r.index: float(r.status == MissionStatus.DONE)
                                   for r in result.records}


def worst_runs(records: list, score: dict[int, float]) -> list:
    """The worst tenth of the scored runs (at least five, at most all) by ``score``, lowest
    first; ties in run order."""
    scored = sorted((r for r in records if r.index in score),
                    key=lambda r: (score[r.index], r.index))
    return scored[:max(5, len(scored) // 10)]


def _axes(records: list, score: dict[int, float]) -> list[tuple[str, float]]:
    """The two drawn quantities most correlated with ``score`` among those every scored run
    has (an injection's time exists only for the runs it occurs in: plotting over it would
    leave the other runs, the worst among them perhaps, out of the figure)."""
    scored = [r for r in records if r.index in score]
    if not scored:
        return []
    common = set.intersection(*(set(r.setting.values) for r in scored))
    return [(name, rho) for name, rho in influence(scored, score) if name in common][:2]


def _scatter(plt: Any, result: CampaignResult) -> Any | None:
    label, score = _score(result)
    ranked = _axes(result.records, score)
    if len(ranked) < 2:
        return None
    (x, rx), (y, ry) = ranked
    runs = [r for r in result.records if r.index in score]
    worst = worst_runs(runs, score)
    fig, ax = plt.subplots(figsize=(6, 4.5))
    ax.scatter([r.setting.values[x] for r in runs], [r.setting.values[y] for r in runs],
               s=10, color="#cccccc", label=f"all {len(runs)} runs")
    points = ax.scatter([r.setting.values[x] for r in worst],
                        [r.setting.values[y] for r in worst],
                        c=[score[r.index] for r in worst], cmap="autumn", s=30,
                        label=f"the {len(worst)} worst by {label}")
    fig.colorbar(points, ax=ax, label=label)
    ax.set_xlabel(f"{x} (|ρ| = {rx:.2f})")
    ax.set_ylabel(f"{y} (|ρ| = {ry:.2f})")
    ax.legend(loc="best", fontsize="small")
    fig.tight_layout()
    return fig


def figures(result: CampaignResult) -> dict[str, Any]:
    """The report's figures by file stem (absent when there is nothing to plot)."""
    plt = _pyplot()
    made = {"outcomes": _outcomes(plt, result), "robustness": _robustness(plt, result),
            "completion_time": _completion(plt, result), "worst_runs": _scatter(plt, result)}
    return {name: fig for name, fig in made.items() if fig is not None}


def _png(fig: Any) -> bytes:
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", dpi=100)
    import matplotlib.pyplot as plt

    plt.close(fig)
    return buffer.getvalue()


def _replays(result: CampaignResult) -> list[tuple[int, str, str]]:
    rows = []
    for index, command in sorted(result.replays.items()):
        record = next(r for r in result.records if r.index == index)
        rows.append((index, record.outcome, command))
    return rows


def write_report(result: CampaignResult, out: str) -> None:
    """Write the report to ``out`` (``.html``: one file; else a folder, see the module)."""
    images = {name: _png(fig) for name, fig in figures(result).items()}
    title = f"Campaign {result.mission} ({result.file}): {len(result.records)} runs"
    if out.endswith(".html"):
        parts = [f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>"
                 f"{html.escape(title)}</title></head><body><h1>{html.escape(title)}</h1>"]
        for name, data in images.items():
            encoded = base64.b64encode(data).decode()
            parts.append(f"<h2>{name.replace('_', ' ')}</h2>"
                         f"<img alt='{name}' src='data:image/png;base64,{encoded}'>")
        parts.append("<h2>replay commands</h2><table border='1'><tr><th>run</th>"
                     "<th>outcome</th><th>command</th></tr>")
        parts += [f"<tr><td>{i}</td><td>{html.escape(o)}</td><td><code>{html.escape(c)}"
                  f"</code></td></tr>" for i, o, c in _replays(result)]
        parts.append("</table></body></html>")
        Path(out).write_text("\n".join(parts), encoding="utf-8")
        return
    folder = Path(out)
    folder.mkdir(parents=True, exist_ok=True)
    lines = [f"# {title}", ""]
    for name, data in images.items():
        (folder / f"{name}.png").write_bytes(data)
        lines += [f"## {name.replace('_', ' ')}", "", f"![{name}]({name}.png)", ""]
    lines += ["## replay commands", "", "| run | outcome | command |", "|---|---|---|"]
    lines += [f"| {i} | {o} | `{c}` |" for i, o, c in _replays(result)]
    (folder / "report.md").write_text("\n".join(lines) + "\n", encoding="utf-8")
