"""The controller of a plan, built: its generated table and automaton, written and compiled.

:func:`build_controller` writes the plan's Module-Task table and the mission's automaton
(:mod:`orccad_app.sil.generate`) into a build folder and compiles them with the runtime
library's sources (:mod:`.compiler`, cached by content) into the controller executable of
lockstep or real time (its ``main``).
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

from orccad_app.diagnostics import OrccadError

from orccad_app.codegen.generate import CProgram
from orccad_app.mission.plan import MissionPlan
from orccad_app.sil.build.compiler import build_executable
from orccad_app.sil.generate.automaton import write_automaton
from orccad_app.sil.generate.table import ModuleTable, write_generated
from orccad_app.sil.generate.tree import controller_table

__all__ = ["Prebuilt", "build_controller", "controller_table"]


@dataclass(frozen=True)
class Prebuilt:
    """A controller built elsewhere (``orccad sil --controller DIR/controller``, from the tree
    of ``orccad codegen --controller``, maybe for another processor): run as it is.

    :param executable: the controller executable (the tree's combined main: real time, or
        ``--lockstep``).
    :param wrapper: a command that runs it (``qemu-aarch64``; empty: run directly, or through
        binfmt).
    """

    executable: Path
    wrapper: tuple[str, ...] = ()

    def checked(self) -> Prebuilt:
        """Itself, once its executable is a file this process may run (else a located
        refusal naming it)."""
        path = self.executable
        if not path.is_file() or not os.access(path, os.X_OK):
            raise OrccadError(f"--controller {path}: not an executable file (build the tree of "
                              f"orccad codegen --controller with make)")
        return self

    @property
    def command(self) -> tuple[str, ...]:
        """The command that starts it, before its arguments."""
        return (*self.wrapper, str(self.executable))


def build_controller(plan: MissionPlan, source: str, build_dir: Path, automaton: CProgram,
                   main: str = "orccad_lockstep.c", extra: tuple[Path, ...] = (),
                   libraries: tuple[str, ...] = ("-lm",)) -> tuple[ModuleTable, Path]:
    """The generated table of ``plan`` and its compiled controller (cached by content), with
    the mission's ``automaton`` (:func:`~orccad_app.sil.generate.automaton.mission_automaton`) linked
    in; ``main``: the controller's main (lockstep or real time), ``extra`` sources."""
    table = controller_table(plan, automaton)
    sources = write_generated(table, build_dir, source, main)
    sources += write_automaton(automaton, plan, table, build_dir)
    name = "orccad_controller" if main == "orccad_lockstep.c" else "orccad_controller_rt"
    return table, build_executable([*sources, *extra], name, libraries)
