"""What the checker verifies: a mission compiled in the composed view, with its run sites.

The composed automaton (the application automaton with the RTA of each ``run`` inlined, see
:mod:`orccad_app.robottask.application`) is what ``orccad run`` executes; the checker also
needs what the lowering knows and the automaton does not keep: which ``run`` statement each
``("rt", X, site)`` label comes from, on which robot, and whether it lies in ``on fatal``.
"""

from __future__ import annotations

from dataclasses import dataclass

from orccad_app.diagnostics import SourceLocation
from orccad_app.lang import ast
from orccad_app.reactive.automaton import Automaton
from orccad_app.reactive.compiler import DEFAULT_MAX_STATES, compile_program
from orccad_app.robottask.application import ApplicationLowerer

__all__ = ["Site", "Composition", "compose", "contains"]


@dataclass(frozen=True)
class Site:
    """One ``run`` statement: its number (the label's ``site``), task, robot, location."""

    number: int
    task: str
    robot: str
    loc: SourceLocation
    on_fatal: bool


@dataclass(frozen=True)
class Composition:
    """A mission's composed automaton and what the checker needs to read it."""

    mission: ast.Mission
    program: ast.Program
    automaton: Automaton
    sites: tuple[Site, ...]

    @property
    def name(self) -> str:
        return self.mission.name


def contains(outer: SourceLocation, inner: SourceLocation) -> bool:
    """Is ``inner``'s start inside ``outer``'s span (same file)?"""
    if outer.file != inner.file or outer.end_line is None:
        return False
    start, end = (outer.line, outer.col), (outer.end_line, outer.end_col or 0)
    return start <= (inner.line, inner.col) <= end


def compose(program: ast.Program, mission: ast.Mission, *,
            max_states: int = DEFAULT_MAX_STATES) -> Composition:
    """Lower and compile ``mission`` in the composed view."""
    lowerer = ApplicationLowerer(program, mission)
    automaton = compile_program(lowerer.lower(), max_states=max_states)
    fatal_block = mission.on_fatal.loc if mission.on_fatal is not None else None
    sites = tuple(
        Site(s.number, s.task.name, s.task.robot, s.stmt.loc,
             fatal_block is not None and contains(fatal_block, s.stmt.loc))
        for s in lowerer.sites)
    return Composition(mission, program, automaton, sites)
