"""The one composition step: a mission lowered with its Robot-Tasks and compiled.

:func:`compose` lowers a mission in the composed view (the application automaton with the RTA
of each ``run`` inlined, :mod:`.application`) and compiles it; the result keeps what the
lowering knows and the automaton does not: the ``run`` sites (:class:`RunSite`, in source
order) and the role of every generated signal (:class:`~.signals.SignalRoles`). The checker
(:mod:`orccad_app.verify`), ``orccad compile`` and the mission layer
(:mod:`orccad_app.mission`) all start from a :class:`Composition`.
"""

from __future__ import annotations

from dataclasses import dataclass

from orccad_app.lang import ast
from orccad_app.reactive.automaton import Automaton
from orccad_app.reactive.compiler import DEFAULT_MAX_STATES, compile_program
from orccad_app.robottask.application import ApplicationLowerer, RunSite
from orccad_app.robottask.signals import SignalRoles

__all__ = ["Composition", "compose"]


@dataclass(frozen=True)
class Composition:
    """A mission's composed automaton and what is needed to read it.

    :param mission: the mission.
    :param program: the program it belongs to.
    :param automaton: the minimized composed automaton.
    :param sites: its ``run`` sites, by number.
    :param roles: the role of every signal the lowering added.
    """

    mission: ast.Mission
    program: ast.Program
    automaton: Automaton
    sites: tuple[RunSite, ...]
    roles: SignalRoles

    @property
    def name(self) -> str:
        """The mission's name."""
        return self.mission.name


def compose(program: ast.Program, mission: ast.Mission, *,
            max_states: int = DEFAULT_MAX_STATES) -> Composition:
    """Lower and compile ``mission`` in the composed view."""
    lowerer = ApplicationLowerer(program, mission)
    automaton = compile_program(lowerer.lower(), max_states=max_states)
    return Composition(mission, program, automaton, tuple(lowerer.sites), lowerer.roles)
