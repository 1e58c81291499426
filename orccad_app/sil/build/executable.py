"""The controller of a plan, built: its generated table and automaton, written and compiled.

:func:`build_controller` writes the plan's Module-Task table and the mission's automaton
(:mod:`orccad_app.sil.generate`) into a build folder and compiles them with the runtime
library's sources (:mod:`.compiler`, cached by content) into the controller executable of
lockstep or real time (its ``main``).
"""

from __future__ import annotations

import dataclasses
import hashlib
from pathlib import Path

from orccad_app.codegen.generate import CProgram
from orccad_app.mission.plan import MissionPlan
from orccad_app.sil.build.compiler import build_executable
from orccad_app.sil.generate.automaton import write_automaton
from orccad_app.sil.generate.table import ModuleTable, module_table, write_generated

__all__ = ["build_controller"]


def build_controller(plan: MissionPlan, source: str, build_dir: Path, automaton: CProgram,
                   main: str = "orccad_lockstep.c", extra: tuple[Path, ...] = (),
                   libraries: tuple[str, ...] = ("-lm",)) -> tuple[ModuleTable, Path]:
    """The generated table of ``plan`` and its compiled controller (cached by content), with
    the mission's ``automaton`` (:func:`~orccad_app.sil.generate.automaton.mission_automaton`) linked
    in; ``main``: the controller's main (lockstep or real time), ``extra`` sources."""
    table = dataclasses.replace(module_table(plan),
                                automaton_digest=hashlib.sha256(
                                    automaton.source.encode()).hexdigest()[:32])
    sources = write_generated(table, build_dir, source, main)
    sources += write_automaton(automaton, plan, table, build_dir)
    name = "orccad_controller" if main == "orccad_lockstep.c" else "orccad_controller_rt"
    return table, build_executable([*sources, *extra], name, libraries)
