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
from typing import Callable

from orccad_app.lang import ast
from orccad_app.reactive.automaton import Automaton
from orccad_app.reactive.compiler import DEFAULT_MAX_STATES, compile_program
from orccad_app.reactive.lazy import LazyAutomaton
from orccad_app.robottask.application import ApplicationLowerer, RunSite
from orccad_app.robottask.signals import SignalRoles

__all__ = ["Composition", "compose"]


@dataclass(frozen=True)
class Composition:
    """A mission's composed automaton and what is needed to read it.

    :param mission: the mission.
    :param program: the program it belongs to.
    :param automaton: the minimized composed automaton, or, for a run, the same automaton
        built on demand (:class:`~orccad_app.reactive.lazy.LazyAutomaton`).
    :param sites: its ``run`` sites, by number.
    :param roles: the role of every signal the lowering added.
    """

    mission: ast.Mission
    program: ast.Program
    automaton: Automaton | LazyAutomaton
    sites: tuple[RunSite, ...]
    roles: SignalRoles

    @property
    def name(self) -> str:
        """The mission's name."""
        return self.mission.name


def compose(program: ast.Program, mission: ast.Mission, *,
            max_states: int = DEFAULT_MAX_STATES, lazy: bool = False,
            progress: Callable[[int], None] | None = None,
            max_transitions: int | None = None,
            defer_double_emissions: bool = False) -> Composition:
    """Lower and compile ``mission`` in the composed view; ``lazy``: build the automaton's
    states as a run reaches them (what ``run``, campaigns and the TUI do); ``progress``: called
    with the number of states explored (a full compile); ``max_transitions``: stop a full
    compile past that many transitions (:class:`~orccad_app.reactive.compiler.TransitionBudgetExceeded`);
    ``defer_double_emissions``: see :func:`~orccad_app.reactive.compiler.compile_program` (a
    lazy automaton always defers)."""
    lowerer = ApplicationLowerer(program, mission)
    kernel = lowerer.lower()
    automaton: Automaton | LazyAutomaton = (
        LazyAutomaton(kernel, max_states=max_states) if lazy
        else compile_program(kernel, max_states=max_states, progress=progress,
                             max_transitions=max_transitions,
                             defer_double_emissions=defer_double_emissions))
    return Composition(mission, program, automaton, tuple(lowerer.sites), lowerer.roles)
