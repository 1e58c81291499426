"""Statistics of a campaign, as UPPAAL SMC gives them (docs/campaigns.md, *Statistics*).

- **Estimates** ``P(event)`` of every outcome (``done``, ``failed``, ``failed(E)``,
  ``aborted``, ``aborted(F)``, ``timeout``, ``crashed``) and of every property holding, with the
  exact binomial (**Clopper–Pearson**) interval at the chosen confidence: for ``k`` successes
  in ``n`` runs, ``[B(α/2; k, n−k+1), B(1−α/2; k+1, n−k)]`` with ``B`` the beta quantile
  (Clopper & Pearson, Biometrika 26(4), 1934).
- **Sequential stopping** (``--epsilon ε --confidence 1−α``): runs go on until every estimate's
  interval half-width is at most ``ε``, capped by the **Chernoff–Hoeffding** bound
  ``N = ⌈ln(2/α) / (2ε²)⌉`` (Hoeffding, JASA 58, 1963; Okamoto 1959), after which
  ``P(|p̂ − p| > ε) ≤ α`` whatever ``p`` — UPPAAL SMC's probability estimation.
- **Hypothesis testing** with Wald's **SPRT** (Wald, Ann. Math. Stat. 16(2), 1945):
  ``P(e) >= θ`` is tested as H0: ``p ≥ θ + δ`` against H1: ``p ≤ θ − δ`` (``δ`` the half-width
  of the *indifference region*, where either answer is acceptable), errors ``α`` (reject H0 when
  true) and ``β`` (accept H0 when false); each run adds ``ln(p1/p0)`` or
  ``ln((1−p1)/(1−p0))`` to the log-likelihood ratio, which stops at ``ln((1−β)/α)`` (H1) or
  ``ln(β/(1−α))`` (H0). ``P(e) <= θ`` swaps the roles. UPPAAL SMC's defaults: ``δ = 0.01``,
  ``α = β = 0.05`` (here ``α = β = 1 − confidence``).
"""

from __future__ import annotations

import math
import re
import statistics
from dataclasses import dataclass
from typing import Any, Iterable

from orccad_app.campaign.adapter import RUN_STATUSES, RunRecord
from orccad_app.diagnostics import OrccadError
from orccad_app.reactive.status import MissionStatus

__all__ = ["clopper_pearson", "chernoff_runs", "Hypothesis", "Sprt", "EventCounts",
           "event_counts", "estimates", "estimates_of", "precise_enough", "summarize",
           "influence"]

_HYPOTHESIS = re.compile(r"^\s*P\(\s*(.+?)\s*\)\s*(>=|<=)\s*([0-9.eE+-]+)\s*$")
_OUTCOMES = RUN_STATUSES


def clopper_pearson(k: int, n: int, confidence: float) -> tuple[float, float]:
    """The exact two-sided interval of a binomial proportion (see the module docstring)."""
    from scipy.stats import beta

    if n == 0:
        return 0.0, 1.0
    alpha = 1.0 - confidence
    low = 0.0 if k == 0 else float(beta.ppf(alpha / 2, k, n - k + 1))
    high = 1.0 if k == n else float(beta.ppf(1 - alpha / 2, k + 1, n - k))
    return low, high


def chernoff_runs(epsilon: float, confidence: float) -> int:
    """Runs after which ``P(|p̂ − p| > ε) ≤ 1 − confidence`` for any ``p``."""
    return math.ceil(math.log(2.0 / (1.0 - confidence)) / (2.0 * epsilon ** 2))


class EventCounts:
    """Per event, the runs where it happened and the runs where it was defined, counted one
    run at a time (a campaign folds its runs in as they come, keeping no record)."""

    __slots__ = ("runs", "_status", "_outcomes", "_holds", "_known")

    def __init__(self) -> None:
        self.runs = 0
        self._status: dict[str, int] = {}
        """Per status or outcome label, the runs with that status or that outcome."""
        self._outcomes: set[str] = set(_OUTCOMES)
        """The events counted: every status, and each outcome label seen."""
        self._holds: dict[str, int] = {}
        self._known: dict[str, int] = {}
        """Per property, the runs where it holds / where its verdict is known."""

    def add(self, record: RunRecord) -> None:
        """Count one run."""
        self.runs += 1
        status = self._status
        status[record.status] = status.get(record.status, 0) + 1
        if record.outcome != record.status:
            status[record.outcome] = status.get(record.outcome, 0) + 1
        self._outcomes.add(record.outcome)
        for name, result in record.properties.items():
            holds = result.holds
            known = self._known.get(name, 0)
            self._known[name] = known if holds is None else known + 1
            self._holds[name] = self._holds.get(name, 0) + (1 if holds else 0)

    def counts(self) -> tuple[dict[str, int], dict[str, int]]:
        """``(hits, defined)``: the outcomes (every status, and each outcome label seen) in
        the order of :data:`_OUTCOMES`, then the properties by name."""
        hits: dict[str, int] = {}
        defined: dict[str, int] = {}
        for name in sorted(self._outcomes, key=_order):
            hits[name] = self._status.get(name, 0)
            defined[name] = self.runs
        for name in sorted(self._holds):
            hits[name] = self._holds[name]
            defined[name] = self._known[name]
        return hits, defined


def event_counts(records: Iterable[RunRecord]) -> tuple[dict[str, int], dict[str, int]]:
    """Per event, the runs where it happened and the runs where it was defined."""
    counts = EventCounts()
    for record in records:
        counts.add(record)
    return counts.counts()


def _order(name: str) -> tuple[int, str]:
    base = name.split("(")[0]
    return (_OUTCOMES.index(base) if base in _OUTCOMES else len(_OUTCOMES), name)


def estimates(records: list[RunRecord], confidence: float) -> dict[str, dict[str, Any]]:
    """``P(event)`` with its Clopper–Pearson interval for every outcome and property."""
    return estimates_of(*event_counts(records), confidence)


def estimates_of(hits: dict[str, int], defined: dict[str, int],
                 confidence: float) -> dict[str, dict[str, Any]]:
    """:func:`estimates` from the counts of :class:`EventCounts`."""
    result = {}
    for name, k in hits.items():
        n = defined[name]
        low, high = clopper_pearson(k, n, confidence)
        result[name] = {"runs": n, "count": k, "p": k / n if n else None,
                        "low": low, "high": high}
    return result


def precise_enough(records: list[RunRecord] | EventCounts, epsilon: float,
                   confidence: float) -> bool:
    """Every estimate's interval half-width is at most ``epsilon`` (on ``records``, or on
    runs already counted)."""
    counts = records if isinstance(records, EventCounts) else None
    if counts is None:
        counts = EventCounts()
        for record in records:  # type: ignore[union-attr]
            counts.add(record)
    if not counts.runs:
        return False
    return all((e["high"] - e["low"]) / 2 <= epsilon
               for e in estimates_of(*counts.counts(), confidence).values() if e["runs"])


@dataclass(frozen=True)
class Hypothesis:
    """``P(event) >= theta`` (or ``<=``)."""

    event: str
    at_least: bool
    theta: float
    text: str

    @classmethod
    def parse(cls, text: str) -> Hypothesis:
        match = _HYPOTHESIS.match(text)
        if match is None:
            raise OrccadError(f"bad --hypothesis {text!r}: expected 'P(EVENT) >= THETA' or "
                              f"'P(EVENT) <= THETA' (EVENT an outcome such as done, "
                              f"aborted(Leak), or a property)")
        event, op, theta = match.groups()
        value = float(theta)
        if not 0 < value < 1:
            raise OrccadError(f"--hypothesis {text!r}: THETA must be in (0, 1)")
        return cls(event, op == ">=", value, text.strip())

    def happened(self, record: RunRecord) -> bool | None:
        if self.event in record.properties:
            return record.properties[self.event].holds
        return record.status == self.event or record.outcome == self.event


class Sprt:
    """Wald's sequential probability ratio test of a :class:`Hypothesis` (module docstring)."""

    def __init__(self, hypothesis: Hypothesis, delta: float, alpha: float, beta: float) -> None:
        theta = hypothesis.theta
        if not (0 < theta - delta and theta + delta < 1):
            raise OrccadError(f"--delta {delta:g}: the indifference region "
                              f"[{theta - delta:g}, {theta + delta:g}] must lie inside (0, 1)")
        self.hypothesis = hypothesis
        self.delta, self.alpha, self.beta = delta, alpha, beta
        self.p0, self.p1 = theta + delta, theta - delta  # H0: p >= p0, H1: p <= p1
        self.upper = math.log((1 - beta) / alpha)
        self.lower = math.log(beta / (1 - alpha))
        self.llr = 0.0
        self.runs = 0
        self.decision: bool | None = None

    def add(self, record: RunRecord) -> bool | None:
        """Account one run; return the decision (``True``: the hypothesis holds) once made."""
        happened = self.hypothesis.happened(record)
        if self.decision is not None or happened is None:
            return self.decision
        self.runs += 1
        if happened:
            self.llr += math.log(self.p1 / self.p0)
        else:
            self.llr += math.log((1 - self.p1) / (1 - self.p0))
        if self.llr >= self.upper:
            self.decision = not self.hypothesis.at_least  # H1 (p <= p1) accepted
        elif self.llr <= self.lower:
            self.decision = self.hypothesis.at_least  # H0 (p >= p0) accepted
        return self.decision

    def as_dict(self) -> dict[str, Any]:
        return {"hypothesis": self.hypothesis.text, "delta": self.delta, "alpha": self.alpha,
                "beta": self.beta, "runs": self.runs, "log_likelihood_ratio": self.llr,
                "decision": None if self.decision is None else
                ("accepted" if self.decision else "rejected")}


def _describe(values: list[float]) -> dict[str, float] | None:
    if not values:
        return None
    ordered = sorted(values)
    return {"n": len(ordered), "min": ordered[0], "p05": _quantile(ordered, 0.05),
            "median": statistics.median(ordered), "mean": statistics.fmean(ordered),
            "p95": _quantile(ordered, 0.95), "max": ordered[-1]}


def _quantile(ordered: list[float], q: float) -> float:
    position = q * (len(ordered) - 1)
    low = math.floor(position)
    high = min(low + 1, len(ordered) - 1)
    return ordered[low] + (ordered[high] - ordered[low]) * (position - low)


def summarize(records: list[RunRecord], closest: int = 5) -> dict[str, Any]:
    """Distributions: completion time, each property's robustness, each metric; and per
    property the runs closest to violation (smallest robustness)."""
    done = [r.sim_time_s for r in records if r.status == MissionStatus.DONE]
    props = sorted({name for r in records for name in r.properties})
    robustness = {}
    worst = {}
    for name in props:
        scored = [(value, r.index) for r in records if name in r.properties
                  if (value := r.properties[name].robustness) is not None]
        robustness[name] = _describe([value for value, _ in scored])
        worst[name] = [{"run": index, "robustness": value}
                       for value, index in sorted(scored)[:closest]]
    metrics = sorted({name for r in records for name in r.metrics})
    return {"completion_time_s": _describe(done),
            "robustness": robustness,
            "metrics": {name: _describe([value for r in records
                                         if (value := r.metrics.get(name)) is not None])
                        for name in metrics},
            "closest_to_violation": worst}


def influence(records: list[RunRecord], score: dict[int, float]) -> list[tuple[str, float]]:
    """Drawn quantities ranked by |Spearman correlation| with ``score`` (run -> value)."""
    from scipy.stats import spearmanr

    names = sorted({name for r in records for name in r.setting.values})
    ranked = []
    for name in names:
        pairs = [(r.setting.values[name], score[r.index]) for r in records
                 if name in r.setting.values and r.index in score]
        if len(pairs) < 3 or len({p[0] for p in pairs}) < 2 or len({p[1] for p in pairs}) < 2:
            continue
        rho = spearmanr([p[0] for p in pairs], [p[1] for p in pairs]).statistic
        if rho == rho:  # not NaN
            ranked.append((name, abs(float(rho))))
    return sorted(ranked, key=lambda item: -item[1])
