"""Inputs raised at given instants of a run: ``--inject SIG@T`` and plant faults.

``SIG@T`` and ``SIG(value)@T`` raise the automaton input ``SIG`` at ``T`` seconds; the value
is written as in the language (``3``, ``2.5``, ``true``, ``[10, 0, 15]`` for a vector) and
typed against the input's declaration by :func:`typed_injection` (an ``int`` fits a ``float``;
numbers finite, integers within 64 bits): a pure input takes no value, a valued one needs one,
and a value of another type is refused, never converted;
``ROBOT.FAULT=VALUE@T`` (``auv.leak=1@120``, ``auv.battery=5%@60``: a trailing ``%`` is
dropped, the fault's unit applies) applies the fault ``FAULT`` of robot ``ROBOT``'s plant.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, replace
from typing import Any, Iterable

from orccad_app.diagnostics import OrccadError, cut, value_excerpt
from orccad_app.lang.limits import MAX_INT, MIN_INT

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
    """

    name: str
    time_ns: int
    value: Any = None
    fault: PlantFault | None = None


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
        value = None if raw is None else _value(raw.strip())
    except ValueError:
        raise OrccadError(f"bad injection {cut(repr(text))}: cannot read the time or the "
                          f"value (expected SIGNAL(VALUE)@SECONDS, VALUE a number, true, "
                          f"false or a vector of numbers [x, y, ...])") from None
    if not seconds >= 0:
        raise OrccadError(f"bad injection {cut(repr(text))}: the time must be >= 0 s")
    return Injection(name, int(round(seconds * 1e9)), value)


def _fault_injection(text: str, fault: PlantFault, raw: str, when: str) -> Injection:
    try:
        seconds = float(when)
        value = _value(raw[:-1].strip() if raw.endswith("%") else raw)
    except ValueError:
        raise OrccadError(f"bad injection {cut(repr(text))}: expected "
                          f"ROBOT.FAULT=VALUE@SECONDS, "
                          f"e.g. auv.leak=1@120 or auv.battery=5%@60") from None
    if not seconds >= 0:
        raise OrccadError(f"bad injection {cut(repr(text))}: the time must be >= 0 s")
    return Injection(str(fault), int(round(seconds * 1e9)), value, fault=fault)


def _value(raw: str) -> Any:
    if raw in ("true", "false"):
        return raw == "true"
    if raw.startswith("[") or raw.endswith("]"):
        if not (raw.startswith("[") and raw.endswith("]")):
            raise ValueError(raw)
        items = [item.strip() for item in raw[1:-1].split(",")]
        if items == [""]:
            return ()
        return tuple(float(item) for item in items)  # ValueError for an empty item
    try:
        return int(raw)
    except ValueError:
        return float(raw)


def _real(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _typed_value(name: str, kind: str, value: Any) -> Any:
    """``value`` as input ``name`` of type ``kind`` carries it; raises naming what fits."""
    if kind == "vector":
        if not isinstance(value, (tuple, list)) or not all(_real(v) for v in value):
            raise OrccadError(f"--inject {name}: {name} carries a vector: write "
                              f"{name}([x, y, ...])@T, got {cut(repr(value))}")
        if not all(math.isfinite(v) for v in value):
            raise OrccadError(f"--inject {name}: every component must be a finite number, "
                              f"got {value_excerpt(value)}")
        return tuple(float(v) for v in value)
    if kind == "bool":
        if not isinstance(value, bool):
            raise OrccadError(f"--inject {name}: {name} carries a bool (true or false), "
                              f"got {cut(repr(value))}")
        return value
    if kind == "int":
        if not isinstance(value, int) or isinstance(value, bool):
            raise OrccadError(f"--inject {name}: {name} carries an int, got {cut(repr(value))}")
        if not MIN_INT <= value <= MAX_INT:
            raise OrccadError(f"--inject {name}: the value is outside the 64-bit integers")
        return value
    if kind in ("float", "duration"):
        if not _real(value):
            raise OrccadError(f"--inject {name}: {name} carries a {kind}, "
                              f"got {cut(repr(value))}")
        if not math.isfinite(value):
            raise OrccadError(f"--inject {name}: the value must be a finite number, "
                              f"got {value}")
        return float(value) if kind == "float" else value
    raise OrccadError(f"--inject {name}: inputs of type {kind} cannot be injected from the "
                      "command line")


def typed_injection(injection: Injection, signal: Any) -> Injection:
    """``injection`` with its value typed against ``signal``, the input's declaration (an
    object with ``name`` and ``type``, ``None`` for a pure signal); raises
    :class:`OrccadError` when it does not fit."""
    if injection.fault is not None:
        return injection
    name, value = injection.name, injection.value
    if signal.type is None:
        if value is not None:
            raise OrccadError(f"--inject {name}: {name} is a pure input: it takes no value "
                              f"(write {name}@T)")
        return injection
    if value is None:
        example = "[x, y, ...]" if signal.type == "vector" else "value"
        raise OrccadError(f"--inject {name}: {name} carries a {signal.type}: write "
                          f"{name}({example})@T")
    return replace(injection, value=_typed_value(name, signal.type, value))


def typed_injections(injections: Iterable[Injection], inputs: Iterable[Any]) -> list[Injection]:
    """Every injection typed against the declared ``inputs``; plant faults and names that
    are not inputs are left as they are (the run reports those with the known names)."""
    declared = {s.name: s for s in inputs}
    return [typed_injection(i, declared[i.name]) if i.name in declared and i.fault is None else i
            for i in injections]
