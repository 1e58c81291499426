"""Lockstep software-in-the-loop: the mission's Module-Tasks computed by the controller process.

``orccad sil FILE --lockstep`` runs the mission as ``orccad run`` does — the same plan, the
same timing model (releases, the declared execution times, the port protocols, the bus), the
same automaton reacting, the same MuJoCo plant — except that **every job's compute happens in
the controller process**, the C Module-Tasks of the generated table, over a Unix socket: one
request per job, answered before the plant goes on. The plant advances by the declared
execution times, never by the machine's speed, so a run is reproducible, and the report equals
``orccad run``'s wherever the C Module-Tasks compute what the Python ones do (bit for bit for
the arm's kinds; within a few ULP for the AUV's distances, see docs/deploy.md).

:class:`LockstepBackend` is the run's Module-Task backend
(:class:`~orccad_app.mission.backend.ModuleTaskBackend`): the executive's timing model as
in-process, the jobs' compute and the automaton's steps in the controller. :func:`lockstep`
builds and starts the controller of a plan
(:func:`~orccad_app.sil.build.executable.build_controller`) and makes each run site start
:class:`~orccad_app.sil.controller.remote.RemoteModule` proxies instead of Python instances
(:func:`~orccad_app.sil.controller.remote.remote_plan`).
"""

from __future__ import annotations

import tempfile
from collections.abc import Iterator
from contextlib import ExitStack, contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from orccad_app.mission.backend import InProcess
from orccad_app.mission.plan import MissionPlan, SiteModules
from orccad_app.mission.reactor import MissionReactor
from orccad_app.sil.build.executable import Prebuilt, build_controller, controller_table
from orccad_app.sil.controller.automaton import ControllerAutomaton
from orccad_app.sil.controller.process import (DEFAULT_HEARTBEAT_S, ControllerProcess)
from orccad_app.sil.controller.remote import ControllerRun, remote_plan
from orccad_app.sil.generate.automaton import MissionProgram, mission_automaton
from orccad_app.sil.generate.table import ModuleTable

__all__ = ["KindDifference", "LockstepBackend", "check_kinds", "lockstep", "random_inputs",
           "start_controller"]


def start_controller(table: ModuleTable, executable: Path,
                     heartbeat_s: float = DEFAULT_HEARTBEAT_S,
                     prebuilt: Prebuilt | None = None) -> ControllerProcess:
    """Start the controller process of ``table`` (a ``prebuilt`` one: its combined main's
    ``--lockstep``, through its wrapper)."""
    if prebuilt is not None:
        return ControllerProcess(prebuilt.executable, len(table.entries), table.digest,
                                 heartbeat_s, ("--lockstep",), prebuilt.wrapper)
    return ControllerProcess(executable, len(table.entries), table.digest, heartbeat_s)


@contextmanager
def lockstep(plan: MissionPlan, source: str, build_dir: Path | None = None,
             heartbeat_s: float = DEFAULT_HEARTBEAT_S,
             automaton: MissionProgram | None = None,
             prebuilt: Prebuilt | None = None) -> Iterator[ControllerRun]:
    """While in the block, a controller process built for ``plan`` runs (written into
    ``build_dir``, a temporary directory by default), with the mission's ``automaton``
    (default :func:`~orccad_app.sil.generate.automaton.mission_automaton` of the plan); the
    block gets it and the plan whose Module-Tasks compute in it (a copy:
    :func:`~orccad_app.sil.controller.remote.remote_plan`). The process is ended and reaped
    when the block ends, however it ends."""
    automaton = automaton or mission_automaton(plan)
    with tempfile.TemporaryDirectory(prefix="orccad-sil-") as scratch:
        if prebuilt is None:
            table, executable = build_controller(plan, source, build_dir or Path(scratch),
                                                 automaton.program)
        else:
            table, executable = controller_table(plan, automaton.program), prebuilt.executable
        controller = start_controller(table, executable, heartbeat_s, prebuilt)
        try:
            yield ControllerRun(controller, table,
                                remote_plan(plan, automaton.automaton, table, controller))
        finally:
            controller.close()


class LockstepBackend(InProcess):
    """``orccad sil --lockstep``: the executive releases, schedules and times the jobs as
    in-process (:class:`~orccad_app.mission.backend.InProcess`), each job's compute is one
    request to the controller process, and the mission's C automaton is stepped there
    (:class:`~orccad_app.sil.controller.automaton.ControllerAutomaton`).

    Made once the façade has planned the mission: the controller is written, built (cached)
    and started; the run runs a copy of the plan with the full automaton
    (:func:`~orccad_app.sil.generate.automaton.mission_automaton`) and sites that start
    proxies (:meth:`run_plan`). :meth:`close` ends and reaps the controller.

    :param plan: the run's plan.
    :param source: the mission file (named in the generated sources).
    :param build_dir: where the generated C goes (default a temporary directory).
    :param heartbeat_s: the controller must answer each request within this [s].
    :param prebuilt: a controller built from ``orccad codegen --controller``'s tree, run
        instead of building one.
    """

    def __init__(self, plan: MissionPlan, source: str, build_dir: Path | None = None,
                 heartbeat_s: float = DEFAULT_HEARTBEAT_S,
                 prebuilt: Prebuilt | None = None) -> None:
        super().__init__()
        self._mission = mission_automaton(plan)
        self._stack = ExitStack()
        started = self._stack.enter_context(
            lockstep(plan, source, build_dir, heartbeat_s, self._mission, prebuilt))
        self.controller: ControllerProcess = started.controller
        """The controller process."""
        self._plan = started.plan
        self.automaton: ControllerAutomaton | None = None
        """The mission's automaton in the controller, once the run is made."""

    def run_plan(self, plan: MissionPlan) -> MissionPlan:
        """A copy of ``plan``: the full automaton, sites whose starts make proxies."""
        return self._plan

    def reactor(self, plan: MissionPlan) -> MissionReactor:
        """The controller's C automaton, stepped over the socket."""
        self.automaton = ControllerAutomaton(self.controller, self._mission.program,
                                             self._mission.automaton)
        return self.automaton

    def close(self) -> None:
        """End and reap the controller."""
        self._stack.close()


@dataclass(frozen=True)
class KindDifference:
    """The first output where a kind's C and its Python disagree (:func:`check_kinds`).

    :param module: the Module-Task (TCS name).
    :param kind: its kind.
    :param job: the job's number (0 the first after ``init``).
    :param t_s: the job's time [s].
    :param port: the output port (``present`` differences name the port too).
    :param python: what the Python kind wrote (``None``: nothing).
    :param c: what the C kind wrote (``None``: nothing).
    """

    module: str
    kind: str
    job: int
    t_s: float
    port: str
    python: Any
    c: Any

    def text(self) -> str:
        """One line naming it."""
        return (f"module-task '{self.module}' (kind {self.kind}), job {self.job} "
                f"(t = {self.t_s:g} s), output {self.port!r}: Python {_shown(self.python)}, "
                f"C {_shown(self.c)}")


def _shown(value: Any) -> str:
    if value is None:
        return "wrote nothing"
    return repr(np.asarray(value, dtype=float).tolist())


def random_inputs(instance: Any, rng: np.random.Generator, scale: float = 1.0) -> dict[str, Any]:
    """Random values for ``instance``'s input ports (each absent one time in ten: "none yet"):
    a ``float`` port a non-negative number, a vector normal with standard deviation
    ``scale``."""
    values: dict[str, Any] = {}
    for port in instance.ports:
        if port.direction != "in" or rng.random() < 0.1:
            continue
        data = rng.normal(0.0, scale, port.dim or 1)
        values[port.name] = float(abs(data[0]) * 10) if port.type == "float" else data
    return values


def _differs(python: Any, c: Any, rtol: float) -> bool:
    want = np.asarray(python, dtype=float)
    have = np.asarray(c, dtype=float)
    if rtol == 0.0:
        return want.shape != have.shape or want.tobytes() != have.tobytes()
    return want.shape != have.shape or not np.allclose(have, want, rtol=rtol, atol=1e-300,
                                                       equal_nan=True)


def check_kinds(plan: MissionPlan, source: str, jobs: int = 100, seed: int = 0,
                scale: float = 1.0, rtol: float = 0.0,
                build_dir: Path | None = None) -> tuple[int, KindDifference | None]:
    """Feed every Module-Task of ``plan``, in C (a lockstep controller built for it) and in
    Python (a fresh instance with the same parameters), the same ``jobs`` random inputs
    (:func:`random_inputs`, drawn from ``seed``) at 1 ms steps; the number of Module-Tasks
    compared and the first output that differs (``None``: none did) — bit for bit when
    ``rtol`` is 0, else within ``rtol`` relative."""
    rng = np.random.default_rng(seed)
    compared = 0
    with lockstep(plan, source, build_dir) as started:
        for site in started.plan.sites:
            remotes = site.fresh_computes()
            pythons = SiteModules.fresh_computes(site)  # new Python instances, same arguments
            for name, remote in remotes.items():
                python = pythons[name]
                python.init()
                remote.init()
                compared += 1
                for job in range(jobs):
                    t_s = 0.001 * job
                    inputs = random_inputs(python, rng, scale)
                    want, got = python.compute(t_s, inputs), remote.compute(t_s, inputs)
                    for port in sorted(set(want) | set(got)):
                        a, b = want.get(port), got.get(port)
                        if a is None or b is None:
                            if a is not b:
                                return compared, KindDifference(name, python.kind.name, job,
                                                                t_s, port, a, b)
                        elif _differs(a, b, rtol):
                            return compared, KindDifference(name, python.kind.name, job, t_s,
                                                            port, a, b)
    return compared, None
