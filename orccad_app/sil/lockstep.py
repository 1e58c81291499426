"""Lockstep software-in-the-loop: the mission's Module-Tasks computed by the controller process.

``orccad sil FILE --lockstep`` runs the mission as ``orccad run`` does — the same plan, the
same timing model (releases, the declared execution times, the port protocols, the bus), the
same automaton reacting, the same MuJoCo plant — except that **every job's compute happens in
the controller process**, the C Module-Tasks of the generated table, over a Unix socket: one
request per job, answered before the plant goes on. The plant advances by the declared
execution times, never by the machine's speed, so a run is reproducible, and the report equals
``orccad run``'s wherever the C Module-Tasks compute what the Python ones do (bit for bit for
the arm's kinds; within a few ULP for the AUV's distances, see docs/deploy.md).

:func:`controller_for` emits and builds the controller of a plan; :func:`remote_sites` makes
each run site start :class:`~orccad_app.sil.remote.RemoteModule` proxies instead of Python
instances.
"""

from __future__ import annotations

import dataclasses
import hashlib
import tempfile
from collections.abc import Iterator, Mapping
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from orccad_app.codegen.generate import CProgram
from orccad_app.mission.plan import MissionPlan, SiteModules
from orccad_app.sil.automaton import mission_automaton, write_automaton
from orccad_app.sil.build import build_executable
from orccad_app.sil.controller import DEFAULT_HEARTBEAT_S, ControllerFailure, ControllerProcess
from orccad_app.sil.emit import ModuleTable, module_table, write_generated
from orccad_app.sil.remote import RemoteModule

__all__ = ["RemoteSite", "controller_for", "lockstep", "remote_sites", "start_controller"]


@dataclasses.dataclass
class RemoteSite(SiteModules):
    """A run site whose starts make proxies to the controller process."""

    controller: Any = None
    table: Any = None
    managed: bool = False
    """The controller starts its Module-Tasks itself (its real-time automaton task)."""
    c_owned: Mapping[str, frozenset[int]] = dataclasses.field(default_factory=dict)
    """Per Module-Task, the parameter words the automaton task alone writes (its type-1
    updates): the proxies never send them."""

    def fresh_computes(self, instance: Any = None) -> dict[str, Any]:
        shadows = super().fresh_computes(instance)
        table: ModuleTable = self.table
        proxies = {}
        for name, shadow in shadows.items():
            index = table.index(name)
            proxies[name] = RemoteModule(self.controller, index, table.entries[index].layout,
                                         shadow, start=not self.managed,
                                         c_owned=self.c_owned.get(name, frozenset()))
        return proxies


class _NotInController:
    """The plan's own compute objects, replaced: a job before a start would be a bug."""

    def __init__(self, name: str) -> None:
        self.name = name

    def compute(self, t_s: float, inputs: Any) -> dict[str, Any]:
        raise ControllerFailure(f"module-task '{self.name}' computed outside the controller "
                                f"process")


def controller_for(plan: MissionPlan, source: str, build_dir: Path, automaton: CProgram,
                   main: str = "orccad_lockstep.c", extra: tuple[Path, ...] = (),
                   libraries: tuple[str, ...] = ("-lm",)) -> tuple[ModuleTable, Path]:
    """The generated table of ``plan`` and its compiled controller (cached by content), with
    the mission's ``automaton`` (:func:`~orccad_app.sil.automaton.mission_automaton`) linked
    in; ``main``: the controller's main (lockstep or real time), ``extra`` sources."""
    table = dataclasses.replace(module_table(plan),
                                automaton_digest=hashlib.sha256(
                                    automaton.source.encode()).hexdigest()[:32])
    sources = write_generated(table, build_dir, source, main)
    sources += write_automaton(automaton, plan, table, build_dir)
    name = "orccad_controller" if main == "orccad_lockstep.c" else "orccad_controller_rt"
    return table, build_executable([*sources, *extra], name, libraries)


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
    it (emitted into ``build_dir``, a temporary directory by default), where the mission's
    ``automaton`` (default :func:`~orccad_app.sil.automaton.mission_automaton` of the plan)
    reacts too; the process is ended and reaped when the block ends, however it ends."""
    automaton = automaton or mission_automaton(plan)
    with tempfile.TemporaryDirectory(prefix="orccad-sil-") as scratch:
        table, executable = controller_for(plan, source, build_dir or Path(scratch), automaton)
        controller = start_controller(table, executable, heartbeat_s)
        try:
            remote_sites(plan, table, controller)
            yield controller
        finally:
            controller.close()
