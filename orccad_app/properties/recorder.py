"""What a run shows its properties: the letters of its instants and uniform signal samples.

:class:`PropertyRecorder` observes a mission run (the mission hook ``on_reaction``, called at
every reaction of the automaton, the periodic ticks included) and keeps:

- **instants** (LTL): one letter per reaction, the set of the monitored atoms true in it, as
  :mod:`orccad_app.robottask.atoms` defines them (the model checker reads the same
  definitions): a signal is present when the reaction has it as an input or emits it;
  ``active(X)`` reads the reactor's state after the reaction; ``done`` / ``failed`` /
  ``aborted`` are true in the reaction where the mission's status becomes so
  (:func:`run_instant`);
- **samples** (signal properties), one per period ``period_ns`` (the mission's tick), sample
  ``k`` standing for ``[k·P, (k+1)·P)``: the monitored ports' true values at ``k·P``
  (:meth:`~orccad_app.executive.plant.MujocoPlant.observe`: no noise, no sensor fault) and the
  event atoms true in some reaction of the interval. ``robot.e`` is the last task error written
  by the control law of a Robot-Task on the robot (zero before the first write).
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Iterable
from typing import Any

import numpy as np

from orccad_app.control.ports import TASK_ERROR
from orccad_app.mission.observer import MissionObserver
from orccad_app.mission.run import MissionRun
from orccad_app.reactive.status import Status
from orccad_app.robottask.atoms import Atoms, InstantView
from orccad_app.robottask.labels import RtLabel

__all__ = ["PropertyRecorder", "run_instant"]


def run_instant(present: Collection[str], status: str, previous: str,
                labels: Callable[[], Iterable[object]]) -> InstantView:
    """What the atoms read of one reaction of a run: the signals ``present`` (its inputs and
    outputs), the mission's ``status`` after it (``previous`` before it: a status atom is
    true where the status becomes so) and the reactor's state ``labels`` after it."""
    return InstantView(present,
                       lambda: {label.task for label in labels() if isinstance(label, RtLabel)},
                       status if status != previous else None)


class PropertyRecorder(MissionObserver):
    """Records a run for its properties (see the module docstring).

    :param mission_run: the run (its reactor's state labels, its plants).
    :param keys: the atom keys the properties mention (``("started", "Dive")``…).
    :param ports: the ``(robot, port)`` pairs the signal properties read.
    :param period_ns: the sampling period of signal properties [ns].
    :param task_errors: robot -> dimension of its task error ``robot.e``, for the robots
        whose ``e`` is read (among ``ports``).
    """

    def __init__(self, mission_run: MissionRun, keys: Iterable[tuple],
                 ports: Iterable[tuple[str, str]], period_ns: int,
                 task_errors: dict[str, int] | None = None) -> None:
        self._run = mission_run
        self.period_ns = period_ns
        self._task_errors = dict(task_errors or {})
        self._error_robot = {site.error_module: site.instance.robot_name
                             for site in mission_run.plan.sites
                             if site.error_module
                             and site.instance.robot_name in self._task_errors}
        self._errors = {robot: np.zeros(dim) for robot, dim in self._task_errors.items()}
        self._atoms = Atoms(mission_run.plan.roles, keys)
        self._ports = sorted(set(ports))
        self._status: str = Status.RUNNING
        self._letters: dict[tuple, frozenset] = {}
        self.letters: list[frozenset] = []
        """One letter per instant (reaction)."""
        self.sample_events: list[set] = []
        """Per sample: the atom keys true in some instant of its interval."""
        self.port_values: dict[tuple[str, str], list[np.ndarray]] = {p: [] for p in self._ports}
        """Per port: one value per sample."""

    def on_reaction(self, t_ns: int, inputs: tuple[str, ...], outputs: tuple[str, ...],
                    status: str) -> None:
        # a letter depends on the signals, the status change and the state (its labels):
        # memoized, the periodic ticks of a long task all share one
        key = (inputs, outputs, status, self._status, self._run.reactor.state)
        letter = self._letters.get(key)
        if letter is None:
            letter = self._letters[key] = self._letter(set(inputs) | set(outputs), status)
        self._status = status
        self.letters.append(letter)
        index = t_ns // self.period_ns
        while len(self.sample_events) <= index:
            self._new_sample()
        self.sample_events[index].update(letter)

    def on_write(self, t_ns: int, module: str, port: str, value: Any) -> None:
        if port == TASK_ERROR and module in self._error_robot:
            self._errors[self._error_robot[module]] = np.array(value, dtype=float)

    def wants_write(self, module: str, port: str) -> bool:
        return port == TASK_ERROR and module in self._error_robot

    def complete_samples(self) -> int:
        """How many samples every series holds (a run interrupted inside
        :meth:`_new_sample` leaves its last sample partial: it is not counted)."""
        return min([len(self.sample_events), *map(len, self.port_values.values())])

    def _new_sample(self) -> None:
        self.sample_events.append(set())
        plants = self._run.plants
        for (robot, port), values in self.port_values.items():
            if port == TASK_ERROR and robot in self._task_errors:
                values.append(self._errors[robot])
            else:
                values.append(plants[robot].observe(port))

    def _letter(self, present: set[str], status: str) -> frozenset:
        reactor = self._run.reactor
        return self._atoms.letter(run_instant(present, status, self._status,
                                              lambda: reactor.labels))

    @property
    def ended(self) -> bool:
        """The mission terminated (its automaton finished)."""
        return bool(self._run.reactor.finished)
