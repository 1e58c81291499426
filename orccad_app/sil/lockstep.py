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
(:func:`remote_sites`).
"""

from __future__ import annotations

import dataclasses
import tempfile
from collections.abc import Iterator
from contextlib import ExitStack, contextmanager
from pathlib import Path
from typing import Any

from orccad_app.codegen.generate import CProgram
from orccad_app.mission.backend import InProcess
from orccad_app.mission.plan import MissionPlan, SiteModules
from orccad_app.mission.reactor import MissionReactor
from orccad_app.reactive.automaton import Automaton
from orccad_app.sil.build.executable import build_controller
from orccad_app.sil.controller.automaton import ControllerAutomaton
from orccad_app.sil.controller.process import (DEFAULT_HEARTBEAT_S, ControllerFailure,
                                              ControllerProcess)
from orccad_app.sil.controller.remote import RemoteSite
from orccad_app.sil.generate.automaton import mission_automaton
from orccad_app.sil.generate.table import ModuleTable

__all__ = ["LockstepBackend", "lockstep", "remote_sites", "start_controller"]


class _NotInController:
    """The plan's own compute objects, replaced: a job before a start would be a bug."""

    def __init__(self, name: str) -> None:
        self.name = name

    def compute(self, t_s: float, inputs: Any) -> dict[str, Any]:
        raise ControllerFailure(f"module-task '{self.name}' computed outside the controller "
                                f"process")


def start_controller(table: ModuleTable, executable: Path,
                     heartbeat_s: float = DEFAULT_HEARTBEAT_S) -> ControllerProcess:
    """Start the controller process of ``table``."""
    return ControllerProcess(executable, len(table.entries), table.digest, heartbeat_s)


def remote_sites(plan: MissionPlan, table: ModuleTable,
                 controller: ControllerProcess) -> None:
    """Make every run site of ``plan`` start its Module-Tasks in ``controller`` (in place:
    the plan's sites are replaced)."""
    sites = []
    for site in plan.sites:
        fields = {f.name: getattr(site, f.name) for f in dataclasses.fields(SiteModules)}
        sites.append(RemoteSite(**fields, controller=controller, table=table))
    plan.sites = sites
    for task in plan.tcs.module_tasks:
        task.compute = _NotInController(task.name)


@contextmanager
def lockstep(plan: MissionPlan, source: str, build_dir: Path | None = None,
             heartbeat_s: float = DEFAULT_HEARTBEAT_S,
             automaton: CProgram | None = None) -> Iterator[ControllerProcess]:
    """While in the block, ``plan``'s Module-Tasks compute in a controller process built for
    it (written into ``build_dir``, a temporary directory by default), where the mission's
    ``automaton`` (default :func:`~orccad_app.sil.generate.automaton.mission_automaton` of the plan)
    reacts too; the process is ended and reaped when the block ends, however it ends."""
    automaton = automaton or mission_automaton(plan)
    with tempfile.TemporaryDirectory(prefix="orccad-sil-") as scratch:
        table, executable = build_controller(plan, source, build_dir or Path(scratch), automaton)
        controller = start_controller(table, executable, heartbeat_s)
        try:
            remote_sites(plan, table, controller)
            yield controller
        finally:
            controller.close()


class LockstepBackend(InProcess):
    """``orccad sil --lockstep``: the executive releases, schedules and times the jobs as
    in-process (:class:`~orccad_app.mission.backend.InProcess`), each job's compute is one
    request to the controller process, and the mission's C automaton is stepped there
    (:class:`~orccad_app.sil.controller.automaton.ControllerAutomaton`).

    Made once the façade has planned the mission: the plan's automaton becomes the full one
    (:func:`~orccad_app.sil.generate.automaton.mission_automaton`), the controller is written,
    built (cached) and started, and the plan's sites start proxies. :meth:`close` ends and
    reaps the controller.

    :param plan: the run's plan.
    :param source: the mission file (named in the generated sources).
    :param build_dir: where the generated C goes (default a temporary directory).
    :param heartbeat_s: the controller must answer each request within this [s].
    """

    def __init__(self, plan: MissionPlan, source: str, build_dir: Path | None = None,
                 heartbeat_s: float = DEFAULT_HEARTBEAT_S) -> None:
        super().__init__()
        self._program = mission_automaton(plan)
        self._stack = ExitStack()
        self.controller: ControllerProcess = self._stack.enter_context(
            lockstep(plan, source, build_dir, heartbeat_s, self._program))
        """The controller process."""
        self.automaton: ControllerAutomaton | None = None
        """The mission's automaton in the controller, once the run is made."""

    def reactor(self, plan: MissionPlan) -> MissionReactor:
        """The controller's C automaton, stepped over the socket."""
        assert isinstance(plan.automaton, Automaton)
        self.automaton = ControllerAutomaton(self.controller, self._program, plan.automaton)
        return self.automaton

    def close(self) -> None:
        """End and reap the controller."""
        self._stack.close()
