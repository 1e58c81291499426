"""The C of a mission's composed automaton: what the lowering knows, passed to the generator.

:func:`generate_mission` generates the C of a :class:`~orccad_app.robottask.composition.
Composition` (the automaton ``orccad check`` proves and ``orccad react --composed`` runs):
the signal roles and the run sites go into the header, and the vector size of every
Robot-Task parameter carried by a run-time argument output (``GoTo.arg.target``) types that
output (and the input it comes from).
"""

from __future__ import annotations

from collections.abc import Iterable

from orccad_app.codegen.circuit import circuit_of, generate_circuit
from orccad_app.codegen.circuit_schedule import NotStatic
from orccad_app.codegen.generate import CProgram, generate
from orccad_app.codegen.names import check_prefix, default_prefix
from orccad_app.codegen.sites import site_infos
from orccad_app.codegen.static_types import CType, CodegenError, Kind
from orccad_app.lang import ast
from orccad_app.lang.run_args import param_type
from orccad_app.reactive import ir
from orccad_app.reactive.automaton import Automaton
from orccad_app.reactive.circuit import Circuit
from orccad_app.reactive.compiler import DEFAULT_MAX_STATES, StateBudgetExceeded, compile_program
from orccad_app.robottask.application import RunSite
from orccad_app.robottask.composition import Composition
from orccad_app.robottask.signals import RoleKind, SignalRoles

__all__ = ["generate_mission", "generate_composed", "generate_chosen", "GENERATORS",
           "default_prefix", "check_prefix"]

#: the generators ``orccad codegen --generator`` names (``auto``: the smaller C, see
#: :func:`generate_chosen`)
GENERATORS = ("auto", "explicit", "circuit")
#: ``auto`` keeps the explicit automaton unless its C has more than this many times the
#: circuit's lines: its step walks one path of a decision tree, the circuit's evaluates every
#: wire
EXPLICIT_FACTOR = 2
#: the explicit automaton is tried while it has at most this many transitions per line of
#: the circuit's C (its C has at most about one line per transition)
TRANSITIONS_PER_LINE = 2 * EXPLICIT_FACTOR


def generate_mission(composition: Composition, prefix: str, origin: str = "") -> CProgram:
    """The C of ``composition``'s automaton (full, not lazy)."""
    return generate_composed(composition.automaton, composition.roles,
                             tuple(composition.sites), composition.program.robottasks,
                             prefix, origin)


def generate_composed(automaton: Automaton | object, roles: SignalRoles,
                      sites: tuple[RunSite, ...], robottasks: Iterable[ast.RobotTask],
                      prefix: str, origin: str = "", note: tuple[str, ...] = ()) -> CProgram:
    """The C of a composed mission automaton from its parts: ``roles`` of its signals, its
    run sites (what each starts goes into the header and the site table, :mod:`.sites`) and
    the program's Robot-Tasks (their parameters type the run-time argument outputs);
    ``note``: header lines saying why this generator."""
    if not isinstance(automaton, Automaton):
        raise CodegenError("the generator needs the full automaton (compiled, not lazy)")
    return generate(automaton, prefix, roles=roles, sites=site_infos(sites),
                    hints=_argument_types(automaton.outputs, roles, robottasks), origin=origin,
                    note=note)


def generate_chosen(composition: Composition, prefix: str, origin: str = "", *,
                    generator: str = "auto", max_states: int = DEFAULT_MAX_STATES) -> CProgram:
    """The C of ``composition`` (lazy or full) by ``generator``: ``explicit`` (the automaton,
    :mod:`.generate`), ``circuit`` (:mod:`.circuit`) or ``auto``: the circuit's C, unless the
    explicit automaton's is at most :data:`EXPLICIT_FACTOR` times larger (its step is a
    decision tree, the fastest) or the circuit's data events have no static order. The
    header says which and why."""
    kernel = composition.automaton.program
    sites = tuple(composition.sites)
    tasks = composition.program.robottasks
    hints = _argument_types(kernel.outputs, composition.roles, tasks)

    def explicit(note: tuple[str, ...], automaton: Automaton | None = None) -> CProgram:
        if automaton is None:
            automaton = compile_program(kernel, max_states=max_states,
                                        defer_double_emissions=True)
        return generate_composed(automaton, composition.roles, sites, tasks, prefix, origin,
                                 ("generator: explicit automaton: " + note[0], *note[1:]))

    def circuit(circuit: Circuit, note: str) -> CProgram:
        return generate_circuit(circuit, prefix, roles=composition.roles,
                                sites=site_infos(sites),
                                hints=hints, origin=origin,
                                note=("generator: circuit: " + note,))

    if generator == "explicit":
        return explicit(("asked for (--generator explicit)",))
    found = circuit_of(kernel)
    try:
        return _choose(found, generator, circuit, explicit, kernel, max_states)
    finally:
        found.manager.release(found)  # CUDD: no node may outlive its manager


def _choose(found: Circuit, generator: str, circuit, explicit, kernel: ir.Program,
            max_states: int) -> CProgram:
    """:func:`generate_chosen` once the circuit is built."""
    if generator == "circuit":
        try:
            return circuit(found, "asked for (--generator circuit)")
        except NotStatic as error:
            raise CodegenError(f"--generator circuit: the circuit's data events have no "
                               f"static order: {error.reason}; the explicit generator orders "
                               "them (--generator explicit)",
                               error.loc or kernel.loc) from None
    try:
        trial = circuit(found, "")
    except NotStatic as error:
        where = f" ({error.loc})" if error.loc is not None else ""
        return explicit((f"the circuit's data events have no static order: {error.reason}"
                         f"{where}",))
    except CodegenError as error:  # e.g. a combination the explicit automaton never makes
        return explicit((f"the circuit's C has no translation: {error.message}",))
    lines = trial.source.count("\n")
    budget = max(1_000, TRANSITIONS_PER_LINE * lines)
    try:
        automaton = compile_program(kernel, max_states=max_states, max_transitions=budget,
                                    defer_double_emissions=True)
    except StateBudgetExceeded:
        return circuit(found, f"the explicit automaton has more than {budget} transitions "
                              f"(or {max_states} states); the circuit's C has {lines} lines")
    small = explicit(("",), automaton)
    explicit_lines = small.source.count("\n")
    if explicit_lines <= EXPLICIT_FACTOR * lines:
        return explicit((f"{explicit_lines} lines of C, the circuit's {lines} (the explicit "
                         f"step is faster: kept up to {EXPLICIT_FACTOR}x the circuit's size)",),
                        automaton)
    return circuit(found, f"{lines} lines of C, the explicit automaton's {explicit_lines}")


def _argument_types(outputs: tuple[ir.SignalDecl, ...], roles: SignalRoles,
                    robottasks: Iterable[ast.RobotTask]) -> dict[ir.SignalDecl, CType]:
    tasks = {task.name: task for task in robottasks}
    hints: dict[ir.SignalDecl, CType] = {}
    for decl in outputs:
        role = roles.get(decl.name)
        if role is None or role.kind is not RoleKind.ARGUMENT or decl.type != "vector":
            continue
        task = tasks.get(role.task or "")
        param = next((p for p in task.params if p.name == role.name), None) if task else None
        static = param_type(param) if param is not None else None
        if static is not None and static.dim:
            hints[decl] = CType(Kind.VECTOR, Kind.FLOAT, static.dim)
    return hints
