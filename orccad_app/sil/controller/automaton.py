"""The mission's automaton in the controller process, stepped: :class:`ControllerAutomaton`.

What the mission layer steps (:class:`~orccad_app.mission.run.MissionRun`'s ``reactor``) when
the automaton runs in the controller: the Python reactor's interface (``step``, ``values``,
``state``, ``status``, ``reason``, ``finished``, ``labels``), each step one ``OP_REACT``
request whose words are those of ``orccad_automaton.h``. The state numbers are the compiled
automaton's (those of ``orccad check`` and ``orccad codegen``); the labels of a state are read
from the plan's automaton, which :func:`~orccad_app.sil.generate.automaton.mission_automaton`
makes the full one.
"""

from __future__ import annotations

import struct
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from orccad_app.codegen.generate import STATUS_CODES, CProgram
from orccad_app.codegen.static_types import Kind
from orccad_app.diagnostics import OrccadError
from orccad_app.reactive.automaton import Automaton
from orccad_app.reactive.status import Status
from orccad_app.reactive.runtime import AutomatonPosition
from orccad_app.sil.controller.process import ControllerProcess, Op
from orccad_app.sil.generate.automaton import HEAD_WORDS, SignalSlot, signal_slots, signal_words

__all__ = ["CStep", "ControllerAutomaton"]

_STATUS_NAMES = {code: name for name, code in STATUS_CODES.items()}
_WORD = struct.Struct("=q")
_REPLY_HEAD = struct.Struct(f"={HEAD_WORDS}q")


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
        self._inputs = {slot.name: slot for slot in signal_slots(interface.inputs, 1)}
        self._outputs = signal_slots(interface.outputs, HEAD_WORDS)
        self._request_words = 1 + signal_words(interface.inputs)
        self._quiet = bytes(8 * (self._request_words - 1))  # no input present
        self.state = automaton.initial
        self.status = Status.RUNNING
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
        body: bytes = self._quiet
        if inputs:
            words = bytearray(self._quiet)
            valued = inputs if isinstance(inputs, Mapping) else {}
            for name in inputs:
                self._encode(words, name, valued.get(name))
            body = bytes(words)
        reply = self._controller.request_words(Op.REACT, _WORD.pack(clock) + body)
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

    def _decode(self, reply: bytes, slot: SignalSlot) -> Any:
        at = 8 * (slot.word + 1)
        kind = slot.element if slot.kind is Kind.VECTOR else slot.kind
        fmt = f"={slot.size}{'d' if kind is Kind.FLOAT else 'q'}"
        items = struct.unpack_from(fmt, reply, at)
        if kind is Kind.BOOL:
            items = tuple(item != 0 for item in items)
        elif kind is Kind.STRING:
            items = tuple(self._strings.names[item] for item in items)
        return items if slot.kind is Kind.VECTOR else items[0]
