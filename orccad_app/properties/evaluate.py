"""Every property of a mission evaluated on one run: verdict and robustness.

The entry point for commands and campaigns::

    monitor = PropertyMonitor(program, mission, mission_run)   # before mission_run.run()
    result = mission_run.run()
    for verdict in monitor.results():                          # after it
        verdict.name, verdict.kind, verdict.verdict, verdict.robustness, verdict.as_dict()

- **LTL properties** (events only, no time bound) are judged by
  :func:`orccad_app.verify.monitor.ltl_verdict` on the run's instants, with the checker's own
  formula translation: ``true`` / ``false`` when the mission ended (the run then stutters
  forever), else the LTL3 verdict (``undecided`` when the finite run cannot decide);
  ``robustness`` is ``None``.
- **Signal properties** (STL) are evaluated on the run's samples (linear in the run)
  (:mod:`orccad_app.verify.stl`): ``robustness`` is the robustness at time 0 in the unit of
  the signals (``unit`` when they share one), ``verdict`` is ``true`` when it is > 0,
  ``false`` when < 0, ``undecided`` when exactly 0 (on the boundary). ``±inf`` when no
  comparison decides it (events alone).

Unknown robots or ports, and time bounds that are not multiples of the sampling period (the
mission's instant period, ``plan.tick_ns``), raise a located :class:`OrccadError` when the
monitor is built, before the run.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from enum import Enum
from typing import Any

import numpy as np

from orccad_app.control.ports import TASK_ERROR
from orccad_app.diagnostics import OrccadError
from orccad_app.lang import ast
from orccad_app.mission.plan import MissionPlan
from orccad_app.mission.run import MissionRun
from orccad_app.properties.recorder import PropertyRecorder
from orccad_app.verify.checker import applicable
from orccad_app.verify.formula import atoms, from_ast
from orccad_app.verify.monitor import LtlMonitor, Verdict, ltl_verdict
from orccad_app.lang.signal_types import formula_unit, port_signals
from orccad_app.verify.stl import StlFormula, UndefinedRobustness, robustness, translate

__all__ = ["PropertyKind", "PropertyResult", "PropertyMonitor", "Verdict", "results_dict"]


class PropertyKind(str, Enum):
    """How a property is judged: ``ltl`` (proved by ``orccad check``, monitored on runs) or
    ``signal`` (Signal Temporal Logic: monitored on runs only)."""

    LTL = "ltl"
    SIGNAL = "signal"


@dataclass(frozen=True)
class PropertyResult:
    """One property's verdict on one run.

    :param name: the property's name (``safe_depth``).
    :param kind: :class:`PropertyKind`.
    :param verdict: :class:`~orccad_app.verify.monitor.Verdict` (true, false, undecided).
    :param robustness: signal properties: the robustness at time 0 (may be ``±inf``);
        ``None`` for LTL properties and when a sampled value was not a number (a diverged
        plant: the verdict is then ``undecided``).
    :param unit: the robustness's unit (``[m]``), ``""`` when unknown or mixed.
    :param samples: the instants (LTL) or samples (signal) the run gave it.
    :param reason: why a signal property has no verdict on the run (its arithmetic has no
        value: a division by zero, a square root of a negative value, an overflow; a sampled
        value that is not a number), else ``None``.
    """

    name: str
    kind: PropertyKind
    verdict: Verdict
    robustness: float | None = None
    unit: str = ""
    samples: int = 0
    reason: str | None = None

    def as_dict(self) -> dict[str, Any]:
        """Strict JSON: ``robustness`` is ``null`` for LTL properties and when infinite (then
        ``robustness_infinite`` is ``"+inf"`` or ``"-inf"``)."""
        value = self.robustness
        finite = value is not None and math.isfinite(value)
        infinite = ("+inf" if value > 0 else "-inf") if value is not None and \
            math.isinf(value) else None
        found = {"name": self.name, "kind": self.kind.value, "verdict": self.verdict.value,
                 "robustness": value if finite else None, "robustness_infinite": infinite,
                 "unit": self.unit, "samples": self.samples}
        if self.reason is not None:  # why there is no verdict
            found["reason"] = self.reason
        return found


def results_dict(results: list[PropertyResult]) -> list[dict[str, Any]]:
    """The JSON form of a run's property results."""
    return [result.as_dict() for result in results]


@dataclass(frozen=True)
class _Signal:
    prop: ast.Property
    stl: StlFormula
    unit: str
    task_errors: dict[str, int]


def _robot_types(plan: MissionPlan) -> dict[str, Any]:
    return {site.instance.robot_name: site.instance.context.robot for site in plan.sites}


def _check_task_error(prop: ast.Property, robot: str, dim: int, plan: MissionPlan) -> None:
    """``robot.e`` was typed as a vector of the robot's joints: every control law on the
    robot must write an error of that size (a Cartesian task may not)."""
    for site in plan.sites:
        if site.instance.robot_name != robot or not site.error_module:
            continue
        module = plan.tcs.modules[site.error_module]
        size = next((port.dim for port in module.ports if port.name == TASK_ERROR), dim)
        if size != dim:
            raise OrccadError(f"property '{prop.name}': {robot}.e has {size} components in "
                              f"Robot-Task '{site.task}', not the robot's {dim} joints",
                              prop.loc)


class PropertyMonitor:
    """Monitors every property of ``mission`` on ``mission_run`` (see the module docstring).

    Build it before ``mission_run.run()`` (it attaches its recorder as an observer), call
    :meth:`results` after.
    """

    def __init__(self, program: ast.Program, mission: ast.Mission,
                 mission_run: MissionRun) -> None:
        self.mission = mission
        plan = mission_run.plan
        self.period_ns = int(plan.tick_ns)
        props = applicable(program.properties, mission)
        self._ltl = [(p, from_ast(p.formula)) for p in props
                     if not ast.is_signal_formula(p.formula)]
        self._signal = [self._signal_property(p, plan, mission_run) for p in props
                        if ast.is_signal_formula(p.formula)]
        keys: set[tuple] = set()
        for _, formula in self._ltl:
            keys |= atoms(formula)
        ports: set[tuple[str, str]] = set()
        task_errors: dict[str, int] = {}
        for signal in self._signal:
            keys |= set(signal.stl.events.values())
            ports |= {(c.robot, c.port) for c in signal.stl.ports.values()}
            task_errors.update(signal.task_errors)
        self.recorder = PropertyRecorder(mission_run, keys, ports, self.period_ns, task_errors)
        self._running: list[LtlMonitor] | None = None
        if props:
            mission_run.add_observer(self.recorder)

    def _signal_property(self, prop: ast.Property, plan: MissionPlan,
                         mission_run: MissionRun) -> _Signal:
        robot_types = _robot_types(plan)
        ports = port_signals(prop.formula, robot_types)
        for robot, _ in ports:
            if robot not in mission_run.plants:  # pragma: no cover - one plant per robot
                raise OrccadError(f"property '{prop.name}': robot '{robot}' has no plant in "
                                  f"mission '{self.mission.name}'", prop.loc)
        errors = {p.robot: p.dim for p in ports.values() if p.task_error}
        for robot, dim in errors.items():
            _check_task_error(prop, robot, dim, plan)
        stl = translate(prop.formula, ports, self.period_ns)
        return _Signal(prop, stl, formula_unit(ports), errors)

    @property
    def properties(self) -> list[ast.Property]:
        """The monitored properties (LTL first, then signal properties)."""
        return [p for p, _ in self._ltl] + [s.prop for s in self._signal]

    def results(self) -> list[PropertyResult]:
        """The verdict of every property on the run recorded so far, in file order."""
        recorder = self.recorder
        found: list[tuple[ast.Property, PropertyResult]] = []
        for prop, formula in self._ltl:
            verdict = ltl_verdict(formula, recorder.letters, recorder.ended)
            found.append((prop, PropertyResult(prop.name, PropertyKind.LTL, verdict,
                                               samples=len(recorder.letters))))
        for signal in self._signal:
            found.append((signal.prop, self._signal_result(signal)))
        found.sort(key=lambda item: (item[0].loc.line, item[0].loc.col))
        return [result for _, result in found]

    def running(self) -> list[PropertyResult]:
        """:meth:`results` during the run, cheaply: an LTL property's verdict reads only the
        instants new since the last call (:class:`~orccad_app.verify.monitor.LtlMonitor`); a
        signal property is evaluated on the whole run so far."""
        recorder = self.recorder
        if self._running is None:
            self._running = [LtlMonitor(formula) for _, formula in self._ltl]
        found: list[tuple[ast.Property, PropertyResult]] = []
        for (prop, _), monitor in zip(self._ltl, self._running):
            verdict = monitor.verdict(recorder.letters, recorder.ended)
            found.append((prop, PropertyResult(prop.name, PropertyKind.LTL, verdict,
                                               samples=len(recorder.letters))))
        for signal in self._signal:
            found.append((signal.prop, self._signal_result(signal)))
        found.sort(key=lambda item: (item[0].loc.line, item[0].loc.col))
        return [result for _, result in found]

    def _signal_result(self, signal: _Signal) -> PropertyResult:
        recorder = self.recorder
        count = recorder.complete_samples()
        samples: dict[str, Any] = {}
        stacked: dict[tuple[str, str], np.ndarray] = {}  # each port: one row per sample
        for name, component in signal.stl.ports.items():
            port = (component.robot, component.port)
            if port not in stacked and count:
                stacked[port] = np.stack([np.asarray(v, dtype=float).reshape(-1) for v in
                                          recorder.port_values[port][:count]])
            samples[name] = stacked[port][:, component.index or 0] if count else []
        for name, key in signal.stl.events.items():
            samples[name] = [math.inf if key in events or key == ("true",) else -math.inf
                             for events in recorder.sample_events[:count]]
        if not count:  # the run never reacted: nothing to judge
            return PropertyResult(signal.prop.name, PropertyKind.SIGNAL, Verdict.UNDECIDED,
                                  None, signal.unit, 0)
        value: float | None = None
        reason = None
        if any(np.isnan(samples[name]).any() for name in signal.stl.ports):
            reason = "a sampled value is not a number (a diverged plant)"
        else:
            try:
                value = robustness(signal.stl, samples)
            except UndefinedRobustness as undefined:
                reason = f"no robustness on this run: {undefined.reason}"
        verdict = (Verdict.UNDECIDED if value is None or value == 0
                   else Verdict.TRUE if value > 0 else Verdict.FALSE)
        return PropertyResult(signal.prop.name, PropertyKind.SIGNAL, verdict, value,
                              signal.unit, count, reason)
