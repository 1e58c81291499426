"""A run's metrics and the spec's ``[[check]]`` bounds on them.

Metrics of one run (``None`` when a run has none, e.g. a task that never ran):

======================================  ==========================================================
``sim_time_s``                          simulated time at the end [s]
``completion_time_s``                   the same when the mission ended ``done``, else ``None``
``max(ROBOT.PORT)`` / ``min(…)``        extrema of a sensor signal's true value (no noise) over
                                        the run, for each of the spec's ``signals``
                                        (``auv.depth`` [m], ``arm.q[1]`` [rad])
``TASK.tracking_error.max`` / ``.rms``  the task error of TASK's control law over its runs
``deadline_misses``                     deadline misses of every Module-Task
======================================  ==========================================================

**Signal extrema** are sampled at every instant some Module-Task reads a sensor of the robot,
when the plant has just been brought to that instant: :meth:`MujocoPlant.observe` reads the
physical value (no noise, no sensor fault) without drawing random numbers, so observing a run
never changes it (a test compares with and without).
"""

from __future__ import annotations

import re
from typing import Any

import numpy as np

from orccad_app.executive.observer import Observer
from orccad_app.mission.run import MissionRun
from orccad_app.reactive.status import MissionStatus

__all__ = ["SignalExtrema", "run_metrics", "check_results"]

_SIGNAL = re.compile(r"^([A-Za-z_]\w*)\.([A-Za-z_]\w*)(?:\[(\d+)\])?$")


class SignalExtrema(Observer):
    """Min and max of chosen plant signals over a run (see the module docstring)."""

    def __init__(self, signals: tuple[str, ...]) -> None:
        self.signals = signals
        self.low: dict[str, float] = {}
        self.high: dict[str, float] = {}
        self._probes: list[tuple[str, Any, str, int | None]] = []
        self._kernel: Any = None
        self._last = -1

    def bind(self, run: MissionRun) -> None:
        """Resolve the signals against the plants of ``run`` (an unknown one is bad input)."""
        from orccad_app.diagnostics import OrccadError

        self._kernel = run.kernel
        for signal in self.signals:
            match = _SIGNAL.match(signal)
            if match is None:  # the spec's parser matched the same pattern
                raise OrccadError(f"metric signal {signal!r}: expected ROBOT.PORT[INDEX]")
            robot, port, index = match.groups()
            plant = run.plants.get(robot)
            if plant is None:
                raise OrccadError(f"signal {signal}: no robot '{robot}' in the mission "
                                  f"(robots: {', '.join(run.plants)})")
            sensors = [p.name for p in plant.resource.outputs]
            if port not in sensors:
                raise OrccadError(f"signal {signal}: robot '{robot}' has no sensor port "
                                  f"'{port}' (sensors: {', '.join(sensors)})")
            dim = int(np.size(plant.observe(port)))
            if index is not None and int(index) >= dim:
                raise OrccadError(f"signal {signal}: port '{port}' has {dim} component(s)")
            if index is None and dim != 1:
                raise OrccadError(f"signal {signal}: port '{port}' is a vector of {dim}: "
                                  f"name a component ({robot}.{port}[0])")
            self._probes.append((signal, plant, port, None if index is None else int(index)))

    def on_read(self, t_ns: int, module: str, port: str, value: Any) -> None:
        if t_ns == self._last:
            return
        self._last = t_ns
        for signal, plant, name, index in self._probes:
            if plant.time_ns != t_ns:
                continue  # not brought to this instant: looking would change the run
            sample = plant.observe(name)
            number = float(sample.ravel()[index or 0])
            if signal not in self.high:
                self.low[signal] = self.high[signal] = number
            else:
                self.low[signal] = min(self.low[signal], number)
                self.high[signal] = max(self.high[signal], number)


def run_metrics(result: Any, extrema: SignalExtrema) -> dict[str, float | None]:
    """The metrics of a run (see the module docstring)."""
    metrics: dict[str, float | None] = {
        "sim_time_s": result.sim_time_ns / 1e9,
        "completion_time_s": (result.sim_time_ns / 1e9 if result.status == MissionStatus.DONE
                              else None),
        "deadline_misses": float(sum(task.deadline_misses
                                     for task in result.stats.tasks.values())),
    }
    for signal in extrema.signals:
        metrics[f"max({signal})"] = extrema.high.get(signal)
        metrics[f"min({signal})"] = extrema.low.get(signal)
    for task in dict.fromkeys(record.name for record in result.robot_tasks):
        rms = result.rms_error(task)
        peaks = [r.errors.max_abs for r in result.robot_tasks
                 if r.name == task and r.errors.count]
        if rms is not None:
            metrics[f"{task}.tracking_error.rms"] = rms
            metrics[f"{task}.tracking_error.max"] = max(peaks)
    return metrics


def check_results(checks: tuple, metrics: dict[str, float | None]
                  ) -> dict[str, tuple[bool | None, float | None]]:
    """Each check's ``(holds, robustness)``: the margin to its bound(s) in the metric's unit,
    the smaller one when it has two; ``(None, None)`` when the run lacks the metric."""
    results: dict[str, tuple[bool | None, float | None]] = {}
    for check in checks:
        value = metrics.get(check.metric)
        if value is None:
            results[check.name] = (None, None)
            continue
        margins = []
        if check.below is not None:
            margins.append(check.below - value)
        if check.above is not None:
            margins.append(value - check.above)
        robustness = min(margins)
        results[check.name] = (robustness > 0, robustness)
    return results
