"""The mission's automaton in the controller process: generated, linked in, stepped.

``orccad sil`` runs the automaton ``orccad check`` proves — the full composed automaton of
the mission, generated as C by ``orccad codegen`` (:func:`~orccad_app.codegen.mission.
generate_composed`) — inside the controller process, beside the Module-Tasks
(``orccad_app/sil/c/orccad_automaton.c``). :func:`mission_automaton` compiles the plan's
automaton in full (the run's is built lazily; a mission past ``max_states`` is refused as
``orccad check`` refuses it) and generates its C; :func:`automaton_files` writes it beside
the Module-Task table with the binding header that names its prefix.

:class:`ControllerAutomaton` is what the mission layer steps
(:class:`~orccad_app.mission.run.MissionRun`'s ``reactor``): the Python reactor's interface
(``step``, ``values``, ``state``, ``status``, ``reason``, ``finished``, ``labels``), each step
one ``OP_REACT`` request whose words are those of ``orccad_automaton.h``. The state numbers
are the compiled automaton's (those of ``orccad check`` and ``orccad codegen``); the labels
of a state are read from the plan's automaton, which :func:`mission_automaton` makes the full
one.
"""

from __future__ import annotations

import struct
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any


from orccad_app.codegen.generate import STATUS_CODES, CProgram
from orccad_app.codegen.interface import CSignal
from orccad_app.codegen.mission import generate_composed
from orccad_app.codegen.static_types import CodegenError, Kind
from orccad_app.diagnostics import OrccadError
from orccad_app.mission.plan import MissionPlan
from orccad_app.reactive.automaton import RUNNING, Automaton
from orccad_app.reactive.compiler import DEFAULT_MAX_STATES, compile_program
from orccad_app.reactive.runtime import AutomatonPosition
from orccad_app.sil.adjust import adjust_lines, c_adjustments
from orccad_app.sil.controller import ControllerProcess, Op
from orccad_app.sil.emit import ModuleTable

__all__ = ["PREFIX", "ControllerAutomaton", "CStep", "automaton_files",
           "binding_header", "managed_sites",
           "mission_automaton", "reaction_words", "write_automaton"]

PREFIX = "orc_mission"
"""The C prefix of the mission's automaton in the controller (``orc_mission_step``)."""
_HEAD_WORDS = 5
_STATUS_NAMES = {code: name for name, code in STATUS_CODES.items()}
_WORD = struct.Struct("=q")
_REPLY_HEAD = struct.Struct(f"={_HEAD_WORDS}q")


def mission_automaton(plan: MissionPlan, max_states: int = DEFAULT_MAX_STATES) -> CProgram:
    """The C of ``plan``'s automaton; the plan's automaton becomes the full one (compiled
    from its program when it was lazy), whose state numbers the C automaton reports. Raises
    a located error for what the generator refuses, or past ``max_states``."""
    automaton = plan.automaton
    if not isinstance(automaton, Automaton):
        automaton = compile_program(automaton.program, max_states=max_states)
        plan.automaton = automaton
    tasks = {site.instance.task.name: site.instance.task for site in plan.sites}
    try:
        return generate_composed(automaton, plan.roles, tuple(site.task for site in plan.sites),
                                 tasks.values(), PREFIX,
                                 origin=f" for the controller of mission {plan.name}")
    except CodegenError as error:
        raise OrccadError(f"orccad sil: the mission's automaton has no C: {error.message}",
                          error.location) from None


def _value_words(signal: CSignal) -> int:
    ctype = signal.ctype
    if ctype is None:
        return 0
    return ctype.size if ctype.kind is Kind.VECTOR else 1


def _words(signals: tuple[CSignal, ...]) -> int:
    return sum(1 + _value_words(signal) for signal in signals)


def reaction_words(program: CProgram) -> int:
    """The words of a reaction's request and reply (``ORC_AUTOMATON_IN_WORDS`` +
    ``ORC_AUTOMATON_OUT_WORDS``)."""
    interface = program.interface
    return 1 + _words(interface.inputs) + _HEAD_WORDS + _words(interface.outputs)


def binding_header(program: CProgram, plan: MissionPlan, table: ModuleTable) -> str:
    """``orccad_automaton_binding.h``: the generated automaton's prefix and word counts for
    the runtime library's ``orccad_automaton.c``; for the real-time automaton task
    (``orccad_rt_automaton.c``) the reaction period, each input's words and the observer
    Module-Task (index in ``table``) whose event raises each event input."""
    interface = program.interface
    slots = _slots(interface.inputs, 1)
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
    inputs = ", ".join(f"{{{slot.word}, {slot.size}}}" for slot in slots) or "{0, 0}"
    return "\n".join([
        "/* GENERATED by orccad sil: do not edit. The mission's automaton in the controller "
        "(orccad_automaton.h). */",
        "#ifndef ORCCAD_AUTOMATON_BINDING_H",
        "#define ORCCAD_AUTOMATON_BINDING_H",
        f'#include "{program.prefix}.h"',
        f"#define ORC_A(name) {program.prefix}_##name",
        f"#define ORC_A_UP(name) {program.prefix.upper()}_##name",
        f"#define ORC_AUTOMATON_IN_WORDS {1 + _words(interface.inputs)}",
        f"#define ORC_AUTOMATON_OUT_WORDS {_HEAD_WORDS + _words(interface.outputs)}",
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
        *adjust_lines(c_adjustments(plan, table, managed_sites(plan)),
                      {slot.name: slot.word for slot in _slots(interface.outputs, _HEAD_WORDS)}),
        "#endif", ""])


def managed_sites(plan: MissionPlan) -> frozenset[int]:
    """The run sites whose lifecycle the real-time automaton task applies itself: those
    without run-time arguments (a start binds those in the supervisor)."""
    return frozenset(site.number for site in plan.sites if not site.arguments)


def _site_table(program: CProgram, plan: MissionPlan, table: ModuleTable) -> tuple[str, str]:
    """The rows and the flat Module-Task list of ``ORC_AUTOMATON_SITES``."""
    starts = {slot.name: slot.word for slot in _slots(program.interface.outputs, _HEAD_WORDS)}
    managed = managed_sites(plan)
    rows, modules = [], []
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
class CStep:
    """One reaction of the C automaton, as the mission layer reads a Python step.

    :param outputs: the outputs emitted, in declaration order.
    :param valued: the valued ones among them.
    :param status: the instant's status (``running``, ``done``, ``failed``, ``aborted``).
    :param target: the state reached.
    :param values: the values of the valued outputs emitted.
    """

    outputs: tuple[str, ...]
    valued: tuple[str, ...]
    status: str
    target: int
    values: dict[str, Any]


@dataclass(frozen=True)
class _Slot:
    name: str
    kind: Kind | None  # None: pure, or a value the automaton never uses
    element: Kind | None
    size: int
    word: int  # the presence word; the value's words follow


def _slots(signals: tuple[CSignal, ...], first: int) -> tuple[_Slot, ...]:
    slots, word = [], first
    for signal in signals:
        ctype = signal.ctype
        slots.append(_Slot(signal.decl.name, ctype.kind if ctype else None,
                           ctype.element if ctype else None, _value_words(signal), word))
        word += 1 + _value_words(signal)
    return tuple(slots)


class ControllerAutomaton(AutomatonPosition):
    """The C automaton of the controller, stepped as the mission layer steps its reactor
    (see the module docstring).

    :param controller: the controller process (its automaton reset at ``HELLO``).
    :param program: the generated C (its interface and string table).
    :param automaton: the compiled automaton it was generated from (labels, terminal state).
    """

    def __init__(self, controller: ControllerProcess, program: CProgram,
                 automaton: Automaton) -> None:
        self._controller = controller
        self.automaton = automaton
        self._strings = program.strings
        self._errors = program.errors
        interface = program.interface
        self._inputs = {slot.name: slot for slot in _slots(interface.inputs, 1)}
        self._outputs = _slots(interface.outputs, _HEAD_WORDS)
        self._request_words = 1 + _words(interface.inputs)
        self._quiet = bytes(8 * (self._request_words - 1))  # no input present
        self.state = automaton.initial
        self.status = RUNNING
        self.reason: str | None = None
        self.instant = 0

    def values(self, step: CStep) -> dict[str, Any]:
        """The values of ``step``'s valued outputs."""
        return step.values

    def step(self, inputs: Mapping[str, Any] | frozenset[str] | set[str] = frozenset(),
             clock_ns: int | None = None) -> CStep:
        """One instant of the C automaton with ``inputs`` present (a mapping gives valued
        inputs their values), at ``clock_ns`` [ns]."""
        clock = 0 if clock_ns is None else clock_ns
        body = bytearray(self._quiet) if inputs else self._quiet
        if inputs:
            valued = inputs if isinstance(inputs, Mapping) else {}
            for name in inputs:
                self._encode(body, name, valued.get(name))
        reply = self._controller.request_words(Op.REACT, _WORD.pack(clock) + bytes(body))
        return self._reacted(reply)

    def input_words(self, name: str, value: Any, at_ns: int) -> bytes:
        """The ``OP_INPUT`` data raising input ``name`` (with ``value``) at ``at_ns``: the
        instant, then the inputs' words of a reaction."""
        body = bytearray(self._quiet)
        self._encode(body, name, value)
        return _WORD.pack(at_ns) + bytes(body)

    def replay(self, words: bytes) -> tuple[int, tuple[str, ...], CStep]:
        """A reaction the automaton task made (its request's then its reply's words, from
        the controller's record): its instant [ns], the inputs present and its step; this
        proxy's state, status and reason follow it."""
        request, reply = words[:8 * self._request_words], words[8 * self._request_words:]
        clock = _WORD.unpack_from(request)[0]
        present = tuple(name for name, slot in self._inputs.items()
                        if _WORD.unpack_from(request, 8 * slot.word)[0])
        return clock, present, self._reacted(reply)

    def _reacted(self, reply: bytes) -> CStep:
        """The step of a reply; the state, status and reason follow it."""
        code, instant, state, reason, emitted = _REPLY_HEAD.unpack_from(reply)
        if code < 0:
            entry = self._errors.entries[-code - 1]
            raise OrccadError(entry.message, entry.loc)
        self.instant += 1
        self.state = state
        self.status = _STATUS_NAMES[code]
        self.reason = self._strings.names[reason] if reason >= 0 else None
        outputs, valued_names, values = [], [], {}
        if emitted:
            for slot in self._outputs:
                if not _WORD.unpack_from(reply, 8 * slot.word)[0]:
                    continue
                outputs.append(slot.name)
                if slot.kind is not None:
                    valued_names.append(slot.name)
                    values[slot.name] = self._decode(reply, slot)
        return CStep(tuple(outputs), tuple(valued_names), _STATUS_NAMES[instant], state,
                     values)

    def _encode(self, body: bytearray, name: str, value: Any) -> None:
        slot = self._inputs.get(name)
        if slot is None:
            raise OrccadError(f"'{name}' is not an input of the mission's automaton")
        at = 8 * (slot.word - 1)  # the body starts after the clock
        _WORD.pack_into(body, at, 1)
        if slot.kind is None or value is None:
            return
        items = tuple(value) if slot.kind is Kind.VECTOR else (value,)
        if len(items) != slot.size:
            raise OrccadError(f"input {name}: a vector of {len(items)} components, the "
                              f"mission's automaton gives it {slot.size}")
        kind = slot.element if slot.kind is Kind.VECTOR else slot.kind
        for index, item in enumerate(items):
            fmt, word = self._word(name, kind, item)
            struct.pack_into(fmt, body, at + 8 * (1 + index), word)

    def _word(self, name: str, kind: Kind | None, item: Any) -> tuple[str, Any]:
        if kind is Kind.FLOAT:
            return "=d", float(item)
        if kind is Kind.STRING:
            index = self._strings.ids.get(item)
            if index is None:
                raise OrccadError(f"input {name}: the string {item!r} is not one the mission "
                                  "names (its C automaton knows only those)")
            return "=q", index
        return "=q", int(item)

    def _decode(self, reply: bytes, slot: _Slot) -> Any:
        at = 8 * (slot.word + 1)
        kind = slot.element if slot.kind is Kind.VECTOR else slot.kind
        fmt = f"={slot.size}{'d' if kind is Kind.FLOAT else 'q'}"
        items = struct.unpack_from(fmt, reply, at)
        if kind is Kind.BOOL:
            items = tuple(item != 0 for item in items)
        elif kind is Kind.STRING:
            items = tuple(self._strings.names[item] for item in items)
        return items if slot.kind is Kind.VECTOR else items[0]
