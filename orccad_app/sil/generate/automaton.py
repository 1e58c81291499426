"""The mission's automaton for the controller process: compiled in full, generated, bound.

``orccad sil`` runs the automaton ``orccad check`` proves — the full composed automaton of
the mission, generated as C by ``orccad codegen`` (:func:`~orccad_app.codegen.mission.
generate_composed`) — inside the controller process, beside the Module-Tasks
(``orccad_app/sil/c/orccad_automaton.c``). :func:`mission_automaton` compiles the plan's
automaton in full (the run's is built lazily; a mission past ``max_states`` is refused as
``orccad check`` refuses it) and generates its C; :func:`automaton_files` writes it beside
the Module-Task table with the binding header that names its prefix. Where each signal sits
in a reaction's words (:func:`signal_slots`) is read by the automaton's proxy in this process
too (:class:`~orccad_app.sil.controller.automaton.ControllerAutomaton`).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from orccad_app.codegen.cexpr import c_string
from orccad_app.codegen.generate import CProgram
from orccad_app.codegen.interface import CSignal
from orccad_app.codegen.mission import generate_composed
from orccad_app.codegen.static_types import CodegenError, Kind
from orccad_app.diagnostics import OrccadError
from orccad_app.mission.plan import MissionPlan
from orccad_app.reactive.automaton import Automaton
from orccad_app.reactive.compiler import DEFAULT_MAX_STATES, compile_program
from orccad_app.sil.generate.adjust import CAdjust, adjust_lines, c_adjustments
from orccad_app.sil.generate.binds import bind_lines, bindable, c_binds
from orccad_app.sil.generate.table import ModuleTable

__all__ = ["HEAD_WORDS", "PREFIX", "MissionProgram", "SignalSlot", "automaton_files", "binding_header",
           "managed_sites", "mission_automaton", "reaction_words", "signal_slots",
           "signal_words", "supervisor_needs", "value_words", "write_automaton"]

PREFIX = "orc_mission"
"""The C prefix of the mission's automaton in the controller (``orc_mission_step``)."""
HEAD_WORDS = 5
"""The words of a reaction's reply before its outputs' (``orccad_automaton.h``)."""


@dataclass(frozen=True)
class MissionProgram:
    """The mission's automaton for the controller.

    :param automaton: the full automaton (compiled from the plan's program when the plan's was
        lazy), whose state numbers the C automaton reports and whose labels the run reads.
    :param program: its C.
    """

    automaton: Automaton
    program: CProgram


def mission_automaton(plan: MissionPlan, max_states: int = DEFAULT_MAX_STATES) -> MissionProgram:
    """The full automaton of ``plan`` and its C (``plan`` is left as it is: a run in the
    controller runs a copy of it with the full automaton). Raises a located error for what
    the generator refuses, or past ``max_states``."""
    automaton = plan.automaton
    if not isinstance(automaton, Automaton):
        automaton = compile_program(automaton.program, max_states=max_states)
    tasks = {site.instance.task.name: site.instance.task for site in plan.sites}
    try:
        program = generate_composed(automaton, plan.roles,
                                    tuple(site.site for site in plan.sites), tasks.values(),
                                    PREFIX, origin=f" for the controller of mission {plan.name}")
    except CodegenError as error:
        raise OrccadError(f"orccad sil: the mission's automaton has no C: {error.message}",
                          error.location) from None
    return MissionProgram(automaton, program)


def value_words(signal: CSignal) -> int:
    ctype = signal.ctype
    if ctype is None:
        return 0
    return ctype.size if ctype.kind is Kind.VECTOR else 1


def signal_words(signals: tuple[CSignal, ...]) -> int:
    """The words of ``signals``: per signal its presence word and its value's."""
    return sum(1 + value_words(signal) for signal in signals)


def reaction_words(program: CProgram) -> int:
    """The words of a reaction's request and reply (``ORC_AUTOMATON_IN_WORDS`` +
    ``ORC_AUTOMATON_OUT_WORDS``)."""
    interface = program.interface
    return 1 + signal_words(interface.inputs) + HEAD_WORDS + signal_words(interface.outputs)


def binding_header(program: CProgram, plan: MissionPlan, table: ModuleTable) -> str:
    """``orccad_automaton_binding.h``: the generated automaton's prefix and word counts for
    the runtime library's ``orccad_automaton.c``; for the real-time automaton task
    (``orccad_rt_automaton.c``) the reaction period, each input's words and the observer
    Module-Task (index in ``table``) whose event raises each event input."""
    interface = program.interface
    slots = signal_slots(interface.inputs, 1)
    words = {slot.name: slot.word for slot in slots}
    events = []
    for site in plan.sites:
        for name, port in site.event_ports.items():
            module = table.index(port.module)
            outputs = table.entries[module].layout.outputs
            if name in words and outputs and outputs[0].name == port.port:
                events.append((module, words[name]))
    pairs = ", ".join(f"{{{a}, {b}}}" for a, b in events) or "{-1, 0}"
    site_rows, site_modules = _site_table(program, plan, table)
    adjusts = c_adjustments(plan, table, managed_sites(plan))
    inputs = ", ".join(f"{{{slot.word}, {slot.size}}}" for slot in slots) or "{0, 0}"
    return "\n".join([
        "/* GENERATED by orccad sil: do not edit. The mission's automaton in the controller "
        "(orccad_automaton.h). */",
        "#ifndef ORCCAD_AUTOMATON_BINDING_H",
        "#define ORCCAD_AUTOMATON_BINDING_H",
        f'#include "{program.prefix}.h"',
        f"#define ORC_A(name) {program.prefix}_##name",
        f"#define ORC_A_UP(name) {program.prefix.upper()}_##name",
        f"#define ORC_AUTOMATON_IN_WORDS {1 + signal_words(interface.inputs)}",
        f"#define ORC_AUTOMATON_OUT_WORDS {HEAD_WORDS + signal_words(interface.outputs)}",
        "/* The real-time automaton task: its period [ns] (the gcd of the Module-Task periods), "
        "each input's",
        " * {presence word, value words} and each observer's {Module-Task, the presence word "
        "of the input its event raises}. */",
        f"#define ORC_AUTOMATON_TICK_NS {plan.tick_ns}LL",
        f"#define ORC_AUTOMATON_N_INPUTS {len(slots)}",
        f"#define ORC_AUTOMATON_INPUT_SLOTS {{{inputs}}}",
        f"#define ORC_AUTOMATON_N_EVENTS {len(events)}",
        f"#define ORC_AUTOMATON_EVENTS {{{pairs}}}",
        "/* Per run site (site order): {managed (its lifecycle applied by the task: no run-time "
        "argument),",
        " * the start output's presence word in the reply (-1: none), first Module-Task in "
        "ORC_AUTOMATON_SITE_MODULES,",
        " * how many, first measuring one, how many, its Robot-Task's number}. */",
        f"#define ORC_AUTOMATON_N_SITES {len(plan.sites)}",
        f"#define ORC_AUTOMATON_SITES {{{site_rows}}}",
        f"#define ORC_AUTOMATON_SITE_MODULES {{{site_modules}}}",
        *adjust_lines(adjusts, {slot.name: slot.word
                                for slot in signal_slots(interface.outputs, HEAD_WORDS)}),
        *bind_lines(*c_binds(plan), {slot.name: slot.word + 1
                                     for slot in signal_slots(interface.outputs, HEAD_WORDS)},
                    table),
        "/* What the controller still leaves to ORCCAD's supervisor (empty: nothing; a "
        "controller alone on the",
        " * robot refuses to start otherwise, saying this). */",
        f"#define ORC_AUTOMATON_SUPERVISOR {c_string('; '.join(supervisor_needs(plan, adjusts)))}",
        "#endif", ""])


def supervisor_needs(plan: MissionPlan, adjusts: tuple[CAdjust, ...]) -> tuple[str, ...]:
    """What of ``plan`` the real-time controller cannot apply alone (``adjusts``: the type-1
    updates it applies): the sites with run-time arguments, the other type-1 updates."""
    managed = managed_sites(plan)
    own = {(adjust.site, adjust.exception) for adjust in adjusts}
    needs = []
    for site in plan.sites:
        if site.number not in managed:
            needs.append(f"the run-time arguments of {site.task} at {site.site.loc}")
            continue
        needs += [f"the type-1 update {exception} of {site.task}"
                  for exception in site.adjustments if (site.number, exception) not in own]
    return tuple(dict.fromkeys(needs))


def managed_sites(plan: MissionPlan) -> frozenset[int]:
    """The run sites whose lifecycle the real-time automaton task applies itself: those
    without run-time arguments, and those whose arguments it binds itself
    (:func:`~orccad_app.sil.generate.binds.bindable`); the others' starts bind their
    arguments in the supervisor."""
    return frozenset(site.number for site in plan.sites if not site.arguments) | bindable(plan)


def _site_table(program: CProgram, plan: MissionPlan, table: ModuleTable) -> tuple[str, str]:
    """The rows and the flat Module-Task list of ``ORC_AUTOMATON_SITES``."""
    starts = {slot.name: slot.word
              for slot in signal_slots(program.interface.outputs, HEAD_WORDS)}
    managed = managed_sites(plan)
    rows: list[str] = []
    modules: list[int] = []
    tasks: dict[str, int] = {}
    for number, site in enumerate(plan.sites):
        assert site.number == number  # the generated phase table's site numbers
        start = starts.get(site.start_signal or "", -1)
        own = [table.index(name) for name in site.modules]
        measuring = [table.index(name) for name in site.measuring]
        task = tasks.setdefault(site.task, len(tasks))
        rows.append(f"{{{int(site.number in managed)}, {start}, {len(modules)}, {len(own)}, "
                    f"{len(modules) + len(own)}, {len(measuring)}, {task}}}")
        modules += own + measuring
    return ", ".join(rows) or "{0, -1, 0, 0, 0, 0, 0}", ", ".join(map(str, modules)) or "0"


def automaton_files(program: CProgram, plan: MissionPlan, table: ModuleTable) -> dict[str, str]:
    """The automaton's generated files for the controller: ``PREFIX.h``, ``PREFIX.c`` and
    the binding header, name -> text."""
    return {**program.files,
            "orccad_automaton_binding.h": binding_header(program, plan, table)}


def write_automaton(program: CProgram, plan: MissionPlan, table: ModuleTable,
                    out_dir: Path) -> list[Path]:
    """Write :func:`automaton_files` into ``out_dir``; the C sources to compile."""
    out_dir.mkdir(parents=True, exist_ok=True)
    for name, text in automaton_files(program, plan, table).items():
        (out_dir / name).write_text(text)
    return [out_dir / f"{program.prefix}.c"]


@dataclass(frozen=True)
class SignalSlot:
    """Where one signal sits in a reaction's words (``orccad_automaton.h``).

    :param name: the signal.
    :param kind: its value's C kind (``None``: pure, or a value the automaton never uses).
    :param element: a vector's element kind.
    :param size: the value's words.
    :param word: the presence word; the value's words follow.
    """

    name: str
    kind: Kind | None  # None: pure, or a value the automaton never uses
    element: Kind | None
    size: int
    word: int  # the presence word; the value's words follow


def signal_slots(signals: tuple[CSignal, ...], first: int) -> tuple[SignalSlot, ...]:
    """The slots of ``signals``, the first presence word at ``first``."""
    slots, word = [], first
    for signal in signals:
        ctype = signal.ctype
        slots.append(SignalSlot(signal.decl.name, ctype.kind if ctype else None,
                           ctype.element if ctype else None, value_words(signal), word))
        word += 1 + value_words(signal)
    return tuple(slots)


