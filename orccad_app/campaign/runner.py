"""A campaign from spec to statistics: draw, dispatch, record, stop, summarize.

:class:`Campaign` draws run ``i``'s setting (:func:`~orccad_app.campaign.setting.draw_setting`),
dispatches it to the backend (pool or Dask), records each finished run in the database at once
and retries a crashed one once. It keeps at most two runs per worker in flight and stops
submitting when

- every run ``0 … runs−1`` is recorded (``--runs``), or
- with ``--epsilon``, every estimate's Clopper–Pearson half-width is at most ``ε`` on the
  runs ``0 … n−1`` (the *prefix*), or the Chernoff–Hoeffding cap is reached, or
- with ``--hypothesis``, the SPRT has decided on the prefix.

``n`` is the smallest prefix length where the rule holds (every length is tested in order,
even when several runs finish at once), so the answer does not depend on which worker was
faster. Statistics are computed on exactly those ``n`` runs; runs finished beyond them stay in
the database.
"""

from __future__ import annotations

import time
from collections import deque
from dataclasses import dataclass, field, replace
from typing import Any, Callable

from orccad_app.campaign.adapter import (BY_EXCEPTION, CRASHED, RUN_STATUSES, CompiledMission,
                                          RunRecord)
from orccad_app.campaign.executor import Job, make_backend
from orccad_app.campaign.setting import RunSetting, draw_setting, replay_command
from orccad_app.campaign.spec import MAX_RUNS, CampaignSpec
from orccad_app.campaign.stats import (EventCounts, Hypothesis, Sprt, chernoff_runs,
                                       estimates, precise_enough, summarize)
from orccad_app.campaign.store import CampaignStore
from orccad_app.campaign.validate import check_spec
from orccad_app.diagnostics import OrccadError
from orccad_app.reactive.status import MissionStatus

__all__ = ["CampaignOptions", "CampaignResult", "Campaign", "PrefixCounts"]


@dataclass
class CampaignOptions:
    """How to run a campaign (the command's options)."""

    runs: int | None = None
    workers: int | None = None
    cluster: Any = None
    db: str = "campaign.db"
    resume: bool = False
    epsilon: float | None = None
    confidence: float = 0.95
    hypothesis: str | None = None
    delta: float = 0.01
    until_s: float | None = None


@dataclass
class CampaignResult:
    """What a campaign concluded (see :meth:`Campaign.run`)."""

    file: str
    mission: str
    records: list[RunRecord]
    estimates: dict[str, dict[str, Any]]
    summary: dict[str, Any]
    stopped_by: str
    confidence: float
    replays: dict[int, str] = field(default_factory=dict)
    sprt: dict[str, Any] | None = None
    interrupted: bool = False
    backend: str = "pool"
    wall_time_s: float = 0.0
    db: str = ""


class Campaign:
    """One campaign (see the module docstring)."""

    def __init__(self, file: str, spec: CampaignSpec, options: CampaignOptions,
                 mission: str | None = None) -> None:
        self.file = file
        self.spec = spec
        self.options = options
        self.compiled = CompiledMission(file, mission or spec.mission)
        self.until_s = (options.until_s or spec.until_s or self.compiled.default_until_s())
        check_spec(self.compiled, spec, self.until_s)
        self.hypothesis = Hypothesis.parse(options.hypothesis) if options.hypothesis else None
        if self.hypothesis is not None:
            self._check_event(self.hypothesis.event)
        self.limit = self._limit()
        self.stop_n = 0
        self._tested = 0  # prefix lengths already tested against the stopping rule
        self.store = CampaignStore(options.db)
        self.store.start({"file": file, "mission": self.compiled.name,
                          "digest": self.compiled.digest, "spec": spec.text,
                          "until_s": repr(self.until_s)}, options.resume)

    def events(self) -> list[str]:
        """What a ``--hypothesis`` may name: the outcomes (with the mission's exceptions), its
        properties and the spec's checks."""
        exceptions = self.compiled.composition.roles.raised_exceptions()
        return [*RUN_STATUSES, *(f"{status}({name})" for status in BY_EXCEPTION
                                 for name in exceptions),
                *self.compiled.property_names(), *(check.name for check in self.spec.checks)]

    def _check_event(self, event: str) -> None:
        """Refuse a misspelt ``--hypothesis`` event (it would never happen: a silent P = 0)."""
        import difflib

        known = self.events()
        if event not in known:
            close = difflib.get_close_matches(event, known, n=3)
            hint = f"; did you mean {', '.join(close)}?" if close else ""
            raise OrccadError(f"--hypothesis: '{event}' is no outcome, property or check of "
                              f"mission {self.compiled.name}{hint} (events: {', '.join(known)})")

    def _limit(self) -> int:
        """The most runs the campaign may make, within ``MAX_RUNS`` (checked before any)."""
        options = self.options
        if options.runs is not None:
            limit, why = options.runs, f"--runs {options.runs}"
        elif options.epsilon is not None:
            limit = chernoff_runs(options.epsilon, options.confidence)
            why = (f"--epsilon {options.epsilon:g} (its Chernoff-Hoeffding bound is {limit} "
                   "runs: give a larger epsilon)")
        else:
            limit, why = self.spec.runs, f"runs = {self.spec.runs}"
        if limit > MAX_RUNS:
            raise OrccadError(f"{why}: more than the {MAX_RUNS} runs a campaign may make")
        return limit

    def setting(self, index: int) -> RunSetting:
        return draw_setting(self.spec, index, self.until_s)

    def replay(self, setting: RunSetting) -> str:
        return replay_command(self.file, self.compiled.name, setting)

    def job(self, index: int, attempt: int = 1) -> Job:
        return Job(self.file, self.compiled.name, self.compiled.digest, self.setting(index),
                   self.spec.signals, self.spec.checks, attempt)

    # -- running -------------------------------------------------------------------------

    def run(self, progress: Callable[[int, int, PrefixCounts], None] | None = None,
            backend: Any = None) -> CampaignResult:
        """Run (or resume) the campaign; ``progress(recorded, limit, prefix)`` after each
        batch of runs (``prefix``: the counts of the runs ``0 … n−1``, :class:`PrefixCounts`).

        The runs are kept in the database, not in memory: the stopping rule and the progress
        fold each run into counts once the prefix reaches it, and the statistics at the end
        read the runs they use back from the database."""
        start = time.perf_counter()
        prefix = PrefixCounts()
        recorded = 0
        for record in self.store.records():  # a resumed database holds this campaign's draws
            if record.setting != self.setting(record.index):
                raise OrccadError(f"--resume: {self.store.path}: run {record.index} holds a "
                                  "setting this campaign does not draw (an edited row?)")
            prefix.waiting[record.index] = record
            recorded += 1
        pending = self.limit - sum(1 for index in self.store.done() if index < self.limit)
        backend = backend or make_backend(self.options.workers, self.options.cluster, pending)
        self.backend = backend
        interrupted = False
        try:
            stopped = self._loop(backend, prefix, recorded, progress)
        except KeyboardInterrupt:
            interrupted, stopped = True, "interrupted"
        finally:
            backend.close(cancel=interrupted)
        bound = self.limit if stopped in ("runs", "interrupted") else self.stop_n
        used = self.store.records(bound)
        return self._result(used, stopped, interrupted, time.perf_counter() - start)

    def _loop(self, backend: Any, prefix: PrefixCounts, recorded: int,
              progress: Callable | None) -> str:
        stored = self.store.done()
        queue = deque(i for i in range(self.limit) if i not in stored)  # <= MAX_RUNS
        del stored
        flying: dict[Any, Job] = {}
        cap = 2 * max(1, getattr(backend, "workers", 1))
        stopped = self._stop(prefix)
        while (queue and stopped is None) or flying:
            while queue and stopped is None and len(flying) < cap:
                job = self.job(queue.popleft())
                flying[backend.submit(job)] = job
            finished = []
            for future in backend.wait(flying):
                job = flying.pop(future)
                record = backend.result(future, job)
                if record.status == CRASHED and job.attempt == 1:
                    retry = replace(job, attempt=2)
                    flying[backend.submit(retry)] = retry
                    continue
                if job.attempt == 2 and record.status != CRASHED:
                    record.error = "retried once after a crash"
                finished.append((record, self.replay(record.setting)))
            self.store.add_many(finished)  # the runs that came back together: one commit
            recorded += len(finished)
            if stopped is None:
                for record, _ in finished:
                    prefix.waiting[record.index] = record
                stopped = self._stop(prefix)
            if backend.broken:
                backend.restart()
            if progress is not None:
                progress(recorded, self.limit, prefix)
        return stopped or "runs"

    def _stop(self, prefix: PrefixCounts) -> str | None:
        """Fold the runs that extend the prefix; why to stop submitting, if it answers.

        The rule is tested at every new prefix length ``n``, in order, and the campaign stops
        at the *smallest* ``n`` where it holds (``stop_n``): when runs finish out of order the
        prefix can grow by several runs at once, and testing only its new length would make
        the answer depend on which worker was faster. The SPRT wins a tie with the precision
        rule.
        """
        epsilon = self.options.epsilon
        while prefix.length in prefix.waiting:
            record = prefix.waiting.pop(prefix.length)
            prefix.add(record)
            if self.hypothesis is not None:
                if prefix.sprt is None:
                    prefix.sprt = self._new_sprt()
                if prefix.sprt.add(record) is not None:
                    self.stop_n = prefix.length
                    return "hypothesis"
            if epsilon is not None and precise_enough(prefix.counts, epsilon,
                                                      self.options.confidence):
                self.stop_n = prefix.length
                return "epsilon"
        self.stop_n = prefix.length
        return None

    def _new_sprt(self) -> Sprt:
        alpha = 1.0 - self.options.confidence
        assert self.hypothesis is not None
        return Sprt(self.hypothesis, self.options.delta, alpha, alpha)

    def _sprt(self, prefix: list[RunRecord]) -> Sprt:
        test = self._new_sprt()
        for record in prefix:
            if test.add(record) is not None:
                break
        return test

    def _result(self, used: list[RunRecord], stopped: str, interrupted: bool,
                wall: float) -> CampaignResult:
        summary = summarize(used)
        wanted = {w["run"] for worst in summary["closest_to_violation"].values() for w in worst}
        wanted |= {r.index for r in used if r.status != MissionStatus.DONE}
        replays = {r.index: self.replay(r.setting) for r in used if r.index in wanted}
        sprt = self._sprt(used).as_dict() if self.hypothesis is not None else None
        if stopped == "runs" and self.options.epsilon is not None and self.options.runs is None:
            stopped = "chernoff bound"
        return CampaignResult(self.file, self.compiled.name, used,
                              estimates(used, self.options.confidence), summary, stopped,
                              self.options.confidence, replays, sprt, interrupted,
                              getattr(self.backend, "name", "pool"), wall, self.store.path)


class PrefixCounts:
    """The runs ``0 … n−1`` recorded so far, as counts (no record kept): ``length`` is ``n``,
    ``done`` how many of them are ``done``; :attr:`waiting` holds the runs that finished
    before an earlier one, until the prefix reaches them."""

    __slots__ = ("length", "done", "counts", "sprt", "waiting")

    def __init__(self) -> None:
        self.length = 0
        self.done = 0
        self.counts = EventCounts()
        self.sprt: Sprt | None = None
        self.waiting: dict[int, RunRecord] = {}

    def add(self, record: RunRecord) -> None:
        """Fold the run ``length`` in."""
        self.length += 1
        self.done += record.status == MissionStatus.DONE
        self.counts.add(record)
