"""Falsification: search the spec's space for the setting that minimizes a property's robustness.

The search space is the spec's: each ``[params]`` / ``[timing]`` entry over its distribution's
support (:attr:`~orccad_app.campaign.distributions.Distribution.bounds`, or its values for
``choice``), each ``[[inject]]``'s occurrence (unless its probability is 0 or 1), time and
value. The run seed is fixed (``run_seed``): the objective is then a function of the setting.

**optuna** drives the search (``tpe``: the Tree-structured Parzen Estimator, ``cmaes``: CMA-ES
over the real dimensions with the categorical ones sampled independently, ``random``: the
baseline), seeded, its study kept in SQLite (``sqlite:///FILE``) so that ``--resume`` adds
trials to it. Trials are asked in batches of one per worker, run on the campaign's backend
(pool or Dask) and told their robustness; a property a run does not define (a metric it lacks)
scores :data:`UNDEFINED`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Callable

from orccad_app.campaign.adapter import CompiledMission, RunRecord
from orccad_app.campaign.executor import Job, make_backend
from orccad_app.campaign.setting import (RunSetting, build_setting, replay_command,
                                         whole_ns_ms, whole_ns_us)
from orccad_app.campaign.spec import CampaignSpec
from orccad_app.campaign.validate import check_spec
from orccad_app.diagnostics import OrccadError

__all__ = ["Falsifier", "FalsifyResult", "SAMPLERS", "UNDEFINED", "MAX_TRIALS",
           "check_study_file"]

SAMPLERS = ("tpe", "cmaes", "random")
MAX_TRIALS = 10_000
"""Most trials a study may hold (``--budget`` plus a resumed study's trials), checked before
the first: the samplers' cost grows with the trials told (TPE's about quadratically: 2 000
trials measured at some 10 s of sampling alone, so 10 000 some 4 minutes and 100 000 hours)."""
UNDEFINED = 1e9
"""Objective of a run on which the property is undefined (the search's placeholder, never
reported as a robustness: :attr:`FalsifyResult.best_robustness` is then ``None``)."""


@dataclass
class FalsifyResult:
    """The search's outcome: the worst run and when a violation was first found."""

    property: str
    sampler: str
    trials: int
    best: RunRecord | None
    best_robustness: float | None
    first_violation: int | None
    replay: str = ""
    history: list[float] = field(default_factory=list)


class Falsifier:
    """Minimize ``prop``'s robustness over ``spec``'s space (see the module docstring)."""

    def __init__(self, file: str, spec: CampaignSpec, prop: str, *, mission: str | None = None,
                 until_s: float | None = None, sampler: str = "tpe", seed: int = 0,
                 run_seed: int = 0, storage: str | None = None, resume: bool = False) -> None:
        try:
            import optuna
        except ImportError:
            raise OrccadError("orccad falsify needs optuna: pip install 'orccad[falsify]'"
                              ) from None
        self.file, self.spec, self.prop = file, spec, prop
        self.compiled = CompiledMission(file, mission or spec.mission)
        self.until_s = until_s or spec.until_s or self.compiled.default_until_s()
        check_spec(self.compiled, spec, self.until_s)
        known = {c.name for c in spec.checks} | set(self.compiled.property_names())
        if prop not in known:
            raise OrccadError(f"--property {prop}: no such property or check (known: "
                              f"{', '.join(sorted(known)) or 'none'})")
        if sampler not in SAMPLERS:
            raise OrccadError(f"--sampler {sampler}: expected one of {', '.join(SAMPLERS)}")
        self.sampler_name, self.run_seed = sampler, run_seed
        optuna.logging.set_verbosity(optuna.logging.WARNING)
        try:
            self.study = optuna.create_study(
                study_name=f"falsify-{self.compiled.name}-{prop}-{sampler}-{seed}",
                storage=storage, sampler=self._sampler(optuna, sampler, seed),
                direction="minimize", load_if_exists=resume)
        except optuna.exceptions.DuplicatedStudyError:
            raise OrccadError(f"{storage} already holds this study: --resume it, or choose "
                              f"another --study") from None
        except Exception as error:  # noqa: BLE001 - re-raised unless the storage's
            if not _storage_error(error, optuna):
                raise
            raise OrccadError(f"--study {storage}: not an optuna study database (corrupt, or "
                              f"another program's: {type(error).__name__})") from None

    @staticmethod
    def _sampler(optuna: Any, name: str, seed: int) -> Any:
        if name == "tpe":
            return optuna.samplers.TPESampler(seed=seed, n_startup_trials=10)
        if name == "cmaes":
            return optuna.samplers.CmaEsSampler(seed=seed, warn_independent_sampling=False)
        return optuna.samplers.RandomSampler(seed=seed)

    def _suggest(self, trial: Any) -> dict[str, Any]:
        values: dict[str, Any] = {}
        for entry in self.spec.params:
            values[entry.target] = _suggest(trial, entry.target, entry.dist)
        for timing in self.spec.timings:  # whole nanoseconds, as --timing takes them
            values[timing.target] = whole_ns_ms(_suggest(trial, timing.target, timing.dist))
        for axis in self.spec.controller:
            name = f"controller.{axis.target}"
            values[name] = whole_ns_us(_suggest(trial, name, axis.dist))
        for number, inject in enumerate(self.spec.injections):
            prefix = f"inject[{number}]"
            if inject.probability in (0.0, 1.0):
                values[f"{prefix}.occurs"] = int(inject.probability)
            else:
                values[f"{prefix}.occurs"] = trial.suggest_categorical(f"{prefix}.occurs",
                                                                       [0, 1])
            if inject.value is not None:
                values[f"{prefix}.value"] = _suggest(trial, f"{prefix}.value", inject.value)
            values[f"{prefix}.time_s"] = round(trial.suggest_float(
                f"{prefix}.time_s", *inject.time.bounds), 6)
        return values

    def setting(self, trial: Any) -> RunSetting:
        values = self._suggest(trial)
        trial.set_user_attr("values", values)  # as run (rounded): the replay rebuilds these
        return build_setting(self.spec, trial.number, self.run_seed, self.until_s, values)

    def run(self, budget: int, workers: int | None = None, cluster: Any = None,
            progress: Callable[[int, int, float | None], None] | None = None) -> FalsifyResult:
        """Run ``budget`` more trials; the worst run over the whole study."""
        held = len(self.study.trials)
        if held + budget > MAX_TRIALS:
            told = f"{held} trials in the study and " if held else ""
            raise OrccadError(f"--budget {budget}: {told}{budget} more exceed the {MAX_TRIALS} "
                              f"trials a falsification may hold (the sampler's cost grows "
                              f"with them)")
        backend = make_backend(workers, cluster, budget)
        batch = max(1, getattr(backend, "workers", 1))
        records: dict[int, RunRecord] = {}
        history: list[float] = []
        first = _first_violation(self.study)
        try:
            left = budget
            while left > 0:
                trials = [self.study.ask() for _ in range(min(batch, left))]
                left -= len(trials)
                jobs = {t.number: Job(self.file, self.compiled.name, self.compiled.digest,
                                      self.setting(t), self.spec.signals, self.spec.checks)
                        for t in trials}
                futures = {backend.submit(job): (t, job)
                           for t, job in zip(trials, jobs.values())}
                for future, (trial, job) in futures.items():
                    record = backend.result(future, job)
                    score = self._score(record)
                    records[trial.number] = record
                    self.study.tell(trial, score)
                    history.append(score)
                    if score < 0 and first is None:
                        first = trial.number
                    if progress is not None:
                        progress(len(history), budget, self.study.best_value)
        finally:
            backend.close()
        return self._result(records, first, history)

    def _score(self, record: RunRecord) -> float:
        result = record.properties.get(self.prop)
        if result is None or result.robustness is None or not math.isfinite(result.robustness):
            if result is not None and result.holds is False:
                return -1.0  # violated without a quantitative margin
            return UNDEFINED
        return float(result.robustness)

    def _result(self, records: dict[int, RunRecord], first: int | None,
                history: list[float]) -> FalsifyResult:
        best_trial = self.study.best_trial if self.study.trials else None
        best = None
        replay = ""
        if best_trial is not None:
            setting = build_setting(self.spec, best_trial.number, self.run_seed, self.until_s,
                                    best_trial.user_attrs["values"])
            best = records.get(best_trial.number)
            replay = replay_command(self.file, self.compiled.name, setting)
            if best is None:  # found in an earlier (resumed) session
                best = RunRecord(setting, "unknown", None, "unknown", 0.0, 0.0)
        value = best_trial.value if best_trial is not None else None
        if value is not None and value >= UNDEFINED:  # never defined: no robustness to report
            value = None
        return FalsifyResult(self.prop, self.sampler_name, len(self.study.trials), best,
                             value, first, replay, history)


def _suggest(trial: Any, name: str, dist: Any) -> Any:
    choices = dist.choices
    if choices is not None:
        return choices[0] if len(choices) == 1 else trial.suggest_categorical(name,
                                                                               list(choices))
    low, high = dist.bounds
    if dist.integral:
        return trial.suggest_int(name, int(low), int(high))
    return float(f"{trial.suggest_float(name, low, high):.6g}")


def check_study_file(path: str) -> None:
    """Refuse, before optuna writes to it, an existing SQLite file ``path`` that holds tables
    but no optuna study (a campaign's database, another program's file): optuna would add
    its tables beside them."""
    import sqlite3

    from orccad_app.campaign.store import COLUMNS, connect_read_only, table_names

    try:
        db = connect_read_only(path)
        try:
            tables = table_names(db)
        finally:
            db.close()
    except sqlite3.DatabaseError:
        return  # not SQLite: optuna's storage says so (Falsifier)
    if tables and "studies" not in tables:
        what = ("a campaign database: it is orccad campaign's --db" if set(COLUMNS) <= tables
                else "another program's file")
        shown = ", ".join(sorted(tables)[:6]) + (", ..." if len(tables) > 6 else "")
        raise OrccadError(f"{path}: not an optuna study database (it holds the tables "
                          f"{shown}: {what})")


def _storage_error(error: Exception, optuna: Any) -> bool:
    """An error of optuna's storage: its own, or SQLAlchemy's (optuna's SQLite storage raises
    them on a corrupt file; SQLAlchemy is optuna's dependency, not ours to import)."""
    return isinstance(error, optuna.exceptions.OptunaError) or any(
        cls.__module__.startswith("sqlalchemy.") for cls in type(error).__mro__)


def _first_violation(study: Any) -> int | None:
    for trial in study.trials:
        if trial.value is not None and trial.value < 0:
            return trial.number
    return None
