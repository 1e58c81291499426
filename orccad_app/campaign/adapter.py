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
from dataclasses import dataclass, field
from typing import Any

from orccad_app.campaign.metrics import SignalExtrema, check_results, run_metrics
from orccad_app.campaign.setting import RunSetting
from orccad_app.diagnostics import OrccadError
from orccad_app.mission.result import STATUSES, MissionStatus

__all__ = ["CompiledMission", "RunRecord", "PropertyResult", "execute", "outcome_label",
           "compiled_for", "CRASHED", "RUN_STATUSES", "BY_EXCEPTION"]

CRASHED = "crashed"
"""The status of a campaign run whose worker failed (an internal error, not the mission's)."""

RUN_STATUSES: tuple[str, ...] = (*STATUSES, CRASHED)
"""Every status a campaign run can have: the mission's (:class:`MissionStatus`), or
:data:`CRASHED`."""

BY_EXCEPTION = (MissionStatus.FAILED, MissionStatus.ABORTED, MissionStatus.RECOVERING)
"""The statuses an exception may cause (its name is then the reason)."""


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
    if status in BY_EXCEPTION and reason and reason.isidentifier():
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
        from orccad_app.mission.overrides import plan_with_overrides

        return plan_with_overrides(self.source, self.mission, setting.options().overrides,
                                   self.composition)

    def default_until_s(self) -> float:
        """``orccad run``'s default horizon for this mission [s]."""
        from orccad_app.session.options import DEFAULT_UNTIL_S

        return float(self.plan(RunSetting(0, 0, 1.0)).run_horizon_s(DEFAULT_UNTIL_S))

    def property_names(self) -> tuple[str, ...]:
        """The mission's declared properties (those each run judges)."""
        from orccad_app.verify.checker import applicable

        return tuple(p.name for p in applicable(self.source.program.properties, self.mission))

    def session(self, setting: RunSetting, observers: tuple = (),
                trace: str | None = None) -> Any:
        """A planned, ready :class:`~orccad_app.session.RunSession` of ``setting`` (bad input
        in it raises a located :class:`OrccadError` here)."""
        from orccad_app.session import RunSession

        return RunSession(self.source, self.mission,
                          setting.options(observers=observers, trace=trace),
                          composition=self.composition)


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
            checks: tuple = (), observers: tuple = (), trace: str | None = None) -> RunRecord:
    """Run ``setting`` (with a trace written to ``trace`` if given) and gather its outcome,
    metrics and property results. Bad input in the setting is an :class:`OrccadError`;
    anything else propagates (a crash)."""
    extrema = SignalExtrema(signals)
    session = compiled.session(setting, observers=(extrema, *observers), trace=trace)
    extrema.bind(session.run)
    report = session.execute()
    result = report.result
    if result.interrupted:
        raise KeyboardInterrupt
    metrics = run_metrics(result, extrema)
    properties = {name: PropertyResult(holds, robustness)
                  for name, (holds, robustness) in check_results(checks, metrics).items()}
    properties.update(_verdicts(report.properties))
    return RunRecord(setting, result.status, result.reason,
                     outcome_label(result.status, result.reason), result.sim_time_ns / 1e9,
                     result.wall_time_s, {k: _finite(v) for k, v in metrics.items()},
                     properties)


def _verdicts(verdicts: Any) -> dict[str, PropertyResult]:
    """The mission's properties judged on the run (:mod:`orccad_app.properties`): ``holds``
    from the verdict (``None`` when undecided), the robustness when finite."""
    found = {}
    for verdict in verdicts:
        holds = {"true": True, "false": False}.get(verdict.verdict.value)
        value = verdict.robustness
        finite = value is not None and math.isfinite(value)
        found[verdict.name] = PropertyResult(holds, value if finite else None)
    return found


def _finite(value: float | None) -> float | None:
    return value if value is None or math.isfinite(value) else None
