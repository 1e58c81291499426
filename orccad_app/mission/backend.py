"""Where a Module-Task's job runs: the :class:`ModuleTaskBackend` a mission run is given.

A :class:`~orccad_app.mission.run.MissionRun` couples the plan's automaton to the executive;
*where* the Module-Tasks' jobs compute and *what* steps the automaton is its backend's, one
typed interface with three implementations:

- :class:`InProcess` (here; ``orccad run``): the executive runs each job's Python ``compute``
  on its simulated processors, the Python :class:`~orccad_app.reactive.runtime.Reactor` reacts;
- ``LockstepBackend`` (:mod:`orccad_app.sil.lockstep`; ``orccad sil --lockstep``): the same
  timing model, each job's compute one request to the controller process, where the mission's
  C automaton is stepped too;
- ``RealtimeBackend`` (:mod:`orccad_app.sil.realtime.backend`; ``orccad sil --realtime``):
  the controller's threads run the jobs and the automaton on the wall clock; this process is
  the plant server, which applies the reactions the controller recorded
  (:meth:`RunHost.apply_reaction`).

The run calls a backend at these points, each documented on :class:`ModuleTaskBackend`:
:meth:`~ModuleTaskBackend.run_plan` and :meth:`~ModuleTaskBackend.reactor` when it is made, :meth:`~ModuleTaskBackend.attach` once its
simulation is built (before any event), :meth:`~ModuleTaskBackend.activate`,
:meth:`~ModuleTaskBackend.kill` and :meth:`~ModuleTaskBackend.reset_ports` as the automaton's
state starts and ends Robot-Tasks, :meth:`~ModuleTaskBackend.take_input` for every input raised,
:meth:`~ModuleTaskBackend.running` around the run, :meth:`~ModuleTaskBackend.finish` on its
result, and the façade :meth:`~ModuleTaskBackend.close` once the run has ended, however.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from typing import Any, Protocol

from orccad_app.executive.kernel import Kernel
from orccad_app.executive.simulation import Simulation
from orccad_app.mission.plan import MissionPlan
from orccad_app.mission.reactor import MissionReactor
from orccad_app.mission.result import RunResult
from orccad_app.reactive.runtime import Reactor
from orccad_app.robottask.labels import Phase

__all__ = ["InProcess", "ModuleTaskBackend", "RunHost"]


class RunHost(Protocol):
    """What a backend sees of the run it serves (a :class:`~orccad_app.mission.run.MissionRun`)."""

    plan: MissionPlan
    kernel: Kernel
    reactor: MissionReactor

    @property
    def phases(self) -> dict[int, Phase]:
        """Site number -> phase of every running Robot-Task (a copy)."""

    def apply_reaction(self, at_ns: int, inputs: tuple[str, ...], step: Any) -> None:
        """Apply a reaction the backend's automaton made at ``at_ns`` to ``inputs`` (its
        ``step``): the observers told, the Robot-Tasks started, killed and updated."""

    def warn(self, source: str, message: str) -> None:
        """Tell the observers (``on_warning``) that something went wrong but the run goes on."""


class ModuleTaskBackend(Protocol):
    """Where the Module-Tasks' jobs run and what steps the automaton (module docstring)."""

    pacing: float | None
    """The wall-clock pacing this backend imposes (simulated s per wall s; real time: 1),
    ``None``: the caller's."""
    input_lead_ns: int
    """How long before its instant an injection is handed to :meth:`take_input` [ns] (an
    automaton on its own clock queues it until then)."""
    reacts_on_ticks: bool
    """The run reacts on its periodic tick (``False``: the backend's automaton keeps its own)."""

    def run_plan(self, plan: MissionPlan) -> MissionPlan:
        """The plan the run runs, from the one it was given (``plan`` itself, or a copy:
        never ``plan`` changed); called first, when the run is made."""

    def reactor(self, plan: MissionPlan) -> MissionReactor:
        """What steps ``plan``'s automaton (the run's plan); called once, when the run is
        made."""

    def attach(self, run: RunHost, simulation: Simulation) -> None:
        """Called once the run's executive ``simulation`` is built, before any event runs."""

    def activate(self, modules: Sequence[str], at_ns: int) -> None:
        """Release ``modules`` from ``at_ns`` on (a Robot-Task's phase starts them)."""

    def kill(self, modules: Sequence[str], at_ns: int) -> None:
        """Stop ``modules`` at ``at_ns`` (an unfinished job is aborted)."""

    def reset_ports(self, modules: Sequence[str], at_ns: int) -> None:
        """Fresh ports for ``modules`` (a Robot-Task starts again: nothing written by its
        previous run is read)."""

    def take_input(self, name: str, value: Any, at_ns: int) -> bool:
        """An input of the automaton raised for ``at_ns``: ``True`` when the backend delivers
        it itself (to an automaton on its own clock), ``False`` when the run reacts to it."""

    def running(self) -> Any:
        """A context manager held around the run's events."""

    def finish(self, result: RunResult) -> RunResult:
        """The run's result, completed with what the backend measured."""

    def close(self) -> None:
        """Release what the backend holds (a controller process); idempotent."""


class InProcess:
    """The executive runs every job's Python ``compute`` on its simulated processors and the
    Python reactor steps the automaton: ``orccad run``."""

    pacing: float | None = None
    input_lead_ns = 0
    reacts_on_ticks = True

    def __init__(self) -> None:
        self._simulation: Simulation | None = None

    def run_plan(self, plan: MissionPlan) -> MissionPlan:
        """``plan`` itself."""
        return plan

    def reactor(self, plan: MissionPlan) -> MissionReactor:
        """A :class:`~orccad_app.reactive.runtime.Reactor` of the plan's automaton."""
        return Reactor(plan.automaton)

    def attach(self, run: RunHost, simulation: Simulation) -> None:
        """Keep the executive the jobs run in."""
        self._simulation = simulation

    @property
    def simulation(self) -> Simulation:
        """The executive the jobs run in (once attached)."""
        if self._simulation is None:
            raise RuntimeError("the backend is not attached to a run")
        return self._simulation

    def activate(self, modules: Sequence[str], at_ns: int) -> None:
        self.simulation.activate(modules, at_ns=at_ns)

    def kill(self, modules: Sequence[str], at_ns: int) -> None:
        self.simulation.kill(modules, at_ns=at_ns)

    def reset_ports(self, modules: Sequence[str], at_ns: int) -> None:
        self.simulation.reset_ports(modules, at_ns=at_ns)

    def take_input(self, name: str, value: Any, at_ns: int) -> bool:
        return False

    @contextmanager
    def running(self) -> Iterator[None]:
        yield

    def finish(self, result: RunResult) -> RunResult:
        return result

    def close(self) -> None:
        pass
