"""The C of a mission's composed automaton: what the lowering knows, passed to the generator.

:func:`generate_mission` generates the C of a :class:`~orccad_app.robottask.composition.
Composition` (the automaton ``orccad check`` proves and ``orccad react --composed`` runs):
the signal roles and the run sites go into the header, and the vector size of every
Robot-Task parameter carried by a run-time argument output (``GoTo.arg.target``) types that
output (and the input it comes from).
"""

from __future__ import annotations

from collections.abc import Iterable

from orccad_app.codegen.generate import CProgram, generate
from orccad_app.codegen.names import check_prefix, default_prefix
from orccad_app.codegen.sites import site_infos
from orccad_app.codegen.static_types import CType, CodegenError, Kind
from orccad_app.lang import ast
from orccad_app.lang.run_args import param_type
from orccad_app.reactive import ir
from orccad_app.reactive.automaton import Automaton
from orccad_app.robottask.application import RunSite
from orccad_app.robottask.composition import Composition
from orccad_app.robottask.signals import RoleKind, SignalRoles

__all__ = ["generate_mission", "generate_composed", "default_prefix", "check_prefix"]


def generate_mission(composition: Composition, prefix: str, origin: str = "") -> CProgram:
    """The C of ``composition``'s automaton (full, not lazy)."""
    return generate_composed(composition.automaton, composition.roles,
                             tuple(composition.sites), composition.program.robottasks,
                             prefix, origin)


def generate_composed(automaton: Automaton | object, roles: SignalRoles,
                      sites: tuple[RunSite, ...], robottasks: Iterable[ast.RobotTask],
                      prefix: str, origin: str = "") -> CProgram:
    """The C of a composed mission automaton from its parts: ``roles`` of its signals, its
    run sites (what each starts goes into the header and the site table, :mod:`.sites`) and
    the program's Robot-Tasks (their parameters type the run-time argument outputs)."""
    if not isinstance(automaton, Automaton):
        raise CodegenError("the generator needs the full automaton (compiled, not lazy)")
    return generate(automaton, prefix, roles=roles, sites=site_infos(sites),
                    hints=_argument_types(automaton, roles, robottasks), origin=origin)


def _argument_types(automaton: Automaton, roles: SignalRoles,
                    robottasks: Iterable[ast.RobotTask]) -> dict[ir.SignalDecl, CType]:
    tasks = {task.name: task for task in robottasks}
    hints: dict[ir.SignalDecl, CType] = {}
    for decl in automaton.outputs:
        role = roles.get(decl.name)
        if role is None or role.kind is not RoleKind.ARGUMENT or decl.type != "vector":
            continue
        task = tasks.get(role.task or "")
        param = next((p for p in task.params if p.name == role.name), None) if task else None
        static = param_type(param) if param is not None else None
        if static is not None and static.dim:
            hints[decl] = CType(Kind.VECTOR, Kind.FLOAT, static.dim)
    return hints
