"""The campaign's one door into the mission layer: compile once, plan and run each setting.

Everything the campaign needs from ``orccad run`` goes through this module, so that a run of
a campaign is exactly ``orccad run FILE --mission M`` with the setting's options
(:meth:`~orccad_app.campaign.setting.RunSetting.run_args`): the same parsing of ``--inject``,
``--set`` and ``--timing``, the same plan, the default processors (fixed priority, no context
switch) and bus (no transfer time), no pacing.

:class:`CompiledMission` loads and compiles the mission once (parse, check, composed
automaton); :func:`execute` then plans (instantiates the Robot-Tasks with the setting's
overrides: cheap) and runs one setting against fresh plants.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Any

from orccad_app.campaign.metrics import SignalExtrema, check_results, run_metrics
from orccad_app.campaign.setting import RunSetting
from orccad_app.diagnostics import OrccadError

__all__ = ["CompiledMission", "RunRecord", "PropertyResult", "execute", "outcome_label",
           "compiled_for"]


@dataclass(frozen=True)
class PropertyResult:
    """A property's result on one run: ``holds`` and ``robustness`` (how far from violation,
    in the signal's unit; negative when violated; ``None`` when not quantitative)."""

    holds: bool | None
    robustness: float | None = None


@dataclass
class RunRecord:
    """What a campaign keeps of one run (one row of the ``runs`` table)."""

    setting: RunSetting
    status: str
    reason: str | None
    outcome: str
    sim_time_s: float
    wall_time_s: float
    metrics: dict[str, float | None] = field(default_factory=dict)
    properties: dict[str, PropertyResult] = field(default_factory=dict)
    attempts: int = 1
    error: str | None = None

    @property
    def index(self) -> int:
        return self.setting.index


def outcome_label(status: str, reason: str | None) -> str:
    """``done``, ``timeout``, ``failed(E)`` / ``aborted(F)`` / ``recovering(F)`` (the
    exception, when the reason is one), else ``failed`` / ``aborted`` / ``recovering``;
    ``crashed`` for an internal error."""
    if status in ("failed", "aborted", "recovering") and reason and reason.isidentifier():
        return f"{status}({reason})"
    return status


class CompiledMission:
    """``FILE``'s mission ``name`` loaded and compiled once (see the module docstring)."""

    def __init__(self, file: str, mission: str | None = None) -> None:
        from orccad_app.pipeline import compose_mission, load, select_mission

        self.file = file
        self.source = load(file)
        self.mission = select_mission(self.source, mission)
        self.name = self.mission.name
        self.digest = self.source.digest  # the file's and its imports' texts
        self.composition = compose_mission(self.source, self.mission, lazy=True)

    def plan(self, setting: RunSetting) -> Any:
        """The mission's plan with ``setting``'s overrides."""
        from orccad_app.mission.overrides import PlanOverrides, plan_with_overrides

        overrides = PlanOverrides.from_arguments(list(setting.sets), list(setting.timings))
        return plan_with_overrides(self.source, self.mission, overrides, self.composition)

    def default_until_s(self) -> float:
        """``orccad run``'s default horizon for this mission [s]."""
        from orccad_app.mission.run import run_horizon_s

        return run_horizon_s(self.plan(RunSetting(0, 0, 1.0)), 60.0)

    def property_names(self) -> tuple[str, ...]:
        """The mission's declared properties (those each run judges)."""
        from orccad_app.verify.checker import applicable

        return tuple(p.name for p in applicable(self.source.program.properties, self.mission))

    def monitor(self, mission_run: Any) -> Any:
        """The monitor judging every property of the mission on ``mission_run`` (attached to
        it: build it before the run), as ``orccad run`` does."""
        from orccad_app.properties import PropertyMonitor

        return PropertyMonitor(self.source.program, self.mission, mission_run)

    def mission_run(self, setting: RunSetting, observers: tuple = ()) -> Any:
        """A ready :class:`~orccad_app.mission.run.MissionRun` of ``setting``."""
        from orccad_app.executive.bus import Bus
        from orccad_app.executive.processor import Processor
        from orccad_app.mission.injection import parse_injection
        from orccad_app.mission.run import MissionRun

        plan = self.plan(setting)
        injections = [parse_injection(text) for text in setting.injections]
        names = dict.fromkeys(task.processor for task in plan.tcs.module_tasks)
        processors = [Processor(name, "fp", 0) for name in names]
        return MissionRun(plan, seed=setting.seed, until_ns=int(round(setting.until_s * 1e9)),
                          injections=injections, processors=processors, bus=Bus(transfer_ns=0),
                          observers=observers)


_CACHE: dict[tuple[str, str | None, str], CompiledMission] = {}


def compiled_for(file: str, mission: str | None, digest: str) -> CompiledMission:
    """The worker's compiled mission (compiled at its first run, then reused); refuses a file
    whose text differs from the campaign's (``digest``)."""
    key = (file, mission, digest)
    compiled = _CACHE.get(key)
    if compiled is None:
        compiled = CompiledMission(file, mission)
        if compiled.digest != digest:
            raise OrccadError(f"{file} on this worker differs from the campaign's file")
        _CACHE[key] = compiled
    return compiled


def execute(compiled: CompiledMission, setting: RunSetting, signals: tuple[str, ...] = (),
            checks: tuple = (), observers: tuple = ()) -> RunRecord:
    """Run ``setting`` and gather its outcome, metrics and property results. Bad input in
    the setting is an :class:`OrccadError`; anything else propagates (a crash)."""
    extrema = SignalExtrema(signals)
    mission_run = compiled.mission_run(setting, observers=(extrema, *observers))
    extrema.bind(mission_run.sim)
    monitor = compiled.monitor(mission_run)
    start = time.perf_counter()
    result = mission_run.run()
    wall = time.perf_counter() - start
    if result.interrupted:
        raise KeyboardInterrupt
    metrics = run_metrics(result, extrema)
    properties = {name: PropertyResult(holds, robustness)
                  for name, (holds, robustness) in check_results(checks, metrics).items()}
    properties.update(_verdicts(monitor))
    return RunRecord(setting, result.status, result.reason,
                     outcome_label(result.status, result.reason), result.sim_time_ns / 1e9,
                     wall, {k: _finite(v) for k, v in metrics.items()}, properties)


def _verdicts(monitor: Any) -> dict[str, PropertyResult]:
    """The mission's properties judged on the run (:mod:`orccad_app.properties`): ``holds``
    from the verdict (``None`` when undecided), the robustness when finite."""
    found = {}
    for verdict in monitor.results():
        holds = {"true": True, "false": False}.get(verdict.verdict.value)
        value = verdict.robustness
        finite = value is not None and math.isfinite(value)
        found[verdict.name] = PropertyResult(holds, value if finite else None)
    return found


def _finite(value: float | None) -> float | None:
    return value if value is None or math.isfinite(value) else None
