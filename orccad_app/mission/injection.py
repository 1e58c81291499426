"""Inputs raised at given instants of a run: ``--inject SIG@T`` and plant faults.

``SIG@T`` and ``SIG(value)@T`` raise the automaton input ``SIG`` at ``T`` seconds; the value
is written as in the language (``3``, ``2.5``, ``true``, ``[10, 0, 15]`` for a vector) and
typed against the input's declaration by :func:`typed_injection` (the literal grammar and
wording of :mod:`orccad_app.lang.literals`: an ``int`` fits a ``float``; numbers finite,
integers within 64 bits): a pure input takes no value, a valued one needs one, and a value of
another type is refused, never converted;
``ROBOT.FAULT=VALUE@T`` (``auv.leak=1@120``, ``auv.battery=5%@60``: a trailing ``%`` is
dropped, the fault's unit applies) applies the fault ``FAULT`` of robot ``ROBOT``'s plant.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field, replace
from typing import Any, Iterable

from orccad_app.diagnostics import OrccadError, cut
from orccad_app.lang.literals import LiteralError, parse_literal, read_literal, typed_value

__all__ = ["Injection", "PlantFault", "parse_injection", "typed_injection", "typed_injections"]

_INJECTION = re.compile(r"^\s*([A-Za-z_][\w.]*)\s*(?:\((.*)\))?\s*@\s*([0-9.eE+-]+)\s*s?\s*$")
_FAULT = re.compile(r"^\s*([A-Za-z_]\w*)\.([A-Za-z_]\w*)\s*=\s*([^@]*?)\s*@\s*([0-9.eE+-]+)\s*s?\s*$")
_FAULT_NAME = re.compile(r"([A-Za-z_]\w*)\.([A-Za-z_]\w*)")


@dataclass(frozen=True)
class PlantFault:
    """A fault of a robot's plant (``ROBOT.FAULT``: ``auv.leak``), which its robot type's
    plant extension declares; not an automaton input."""

    robot: str
    fault: str

    def __str__(self) -> str:
        return f"{self.robot}.{self.fault}"

    @classmethod
    def named(cls, text: str) -> PlantFault | None:
        """The fault ``ROBOT.FAULT`` written as ``text`` (a user's or a record's), ``None``
        if ``text`` is not of that form."""
        match = _FAULT_NAME.fullmatch(text.strip())
        return None if match is None else cls(*match.groups())


@dataclass(frozen=True)
class Injection:
    """An input signal raised at a simulated instant (``--inject Stop@2.5``), or a plant
    fault set (``--inject auv.leak=1@120``).

    :param name: the automaton input (a mission input, or an observer event ``X.E``), or
        the fault's ``ROBOT.FAULT``.
    :param time_ns: when [ns].
    :param value: its value for a valued input, the fault's value, else ``None``.
    :param fault: the plant fault it sets, ``None`` for an automaton input.
    :param text: an input's value as written (``--inject S(TEXT)@T``), read against the
        input's declared type by :func:`typed_injection` (as an input script's value is);
        ``value`` is what its form says until then.
    """

    name: str
    time_ns: int
    value: Any = None
    fault: PlantFault | None = None
    text: str | None = field(default=None, compare=False)


def parse_injection(text: str) -> Injection:
    """``SIG@T``, ``SIG(value)@T`` or the plant fault ``ROBOT.FAULT=VALUE@T`` (``T`` in
    seconds, ``VALUE`` a number with an optional trailing ``%``, or true/false); raise
    :class:`OrccadError`."""
    fault = _FAULT.match(text)
    if fault is not None:
        robot, name, raw, when = fault.groups()
        return _fault_injection(text, PlantFault(robot, name), raw, when)
    match = _INJECTION.match(text)
    if match is None:
        raise OrccadError(f"bad injection {cut(repr(text))}: expected SIGNAL@SECONDS or "
                          f"SIGNAL(value)@SECONDS, e.g. Stop@2.5")
    name, raw, when = match.groups()
    try:
        seconds = float(when)
    except ValueError:
        raise OrccadError(f"bad injection {cut(repr(text))}: cannot read the time (expected "
                          f"SIGNAL@SECONDS or SIGNAL(VALUE)@SECONDS)") from None
    if not seconds >= 0:
        raise OrccadError(f"bad injection {cut(repr(text))}: the time must be >= 0 s")
    if raw is None:
        return Injection(name, int(round(seconds * 1e9)))
    try:
        value = parse_literal(raw)
    except LiteralError:  # typed_injection reads it against the input's type and says why
        value = None
    return Injection(name, int(round(seconds * 1e9)), value, text=raw.strip())


def _fault_injection(text: str, fault: PlantFault, raw: str, when: str) -> Injection:
    expected = "expected ROBOT.FAULT=VALUE@SECONDS, e.g. auv.leak=1@120 or auv.battery=5%@60"
    try:
        seconds = float(when)
    except ValueError:
        raise OrccadError(f"bad injection {cut(repr(text))}: {expected}") from None
    try:
        value = _value(raw[:-1].strip() if raw.endswith("%") else raw)
    except ValueError as error:  # the literal grammar says why (not a finite number, …)
        raise OrccadError(f"bad injection {cut(repr(text))}: {error} ({expected})") from None
    if not seconds >= 0:
        raise OrccadError(f"bad injection {cut(repr(text))}: the time must be >= 0 s")
    return Injection(str(fault), int(round(seconds * 1e9)), value, fault=fault)


def _value(raw: str) -> Any:
    """A value as the literal grammar reads it by its form; ``ValueError`` if not one."""
    try:
        return parse_literal(raw)
    except LiteralError as error:
        raise ValueError(error.message) from None


def typed_injection(injection: Injection, signal: Any) -> Injection:
    """``injection`` with its value typed against ``signal``, the input's declaration (an
    object with ``name`` and ``type``, ``None`` for a pure signal); raises
    :class:`OrccadError` when it does not fit."""
    if injection.fault is not None:
        return injection
    name, value, text = injection.name, injection.value, injection.text
    if signal.type is None:
        if value is not None or text is not None:
            raise OrccadError(f"--inject {name}: {name} is a pure input: it takes no value "
                              f"(write {name}@T)")
        return injection
    if value is None and text is None:
        example = "[x, y, ...]" if signal.type == "vector" else "value"
        raise OrccadError(f"--inject {name}: {name} carries a {signal.type}: write "
                          f"{name}({example})@T")
    try:
        typed = (typed_value(value, signal.type, name) if text is None
                 else read_literal(text, signal.type, name))
        return replace(injection, value=typed, text=None)
    except LiteralError as error:
        raise OrccadError(f"--inject {name}: {error.message}") from None


def typed_injections(injections: Iterable[Injection], inputs: Iterable[Any]) -> list[Injection]:
    """Every injection typed against the declared ``inputs``; plant faults and names that
    are not inputs are left as they are (the run reports those with the known names)."""
    declared = {s.name: s for s in inputs}
    return [typed_injection(i, declared[i.name]) if i.name in declared and i.fault is None else i
            for i in injections]
