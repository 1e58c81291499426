"""Inputs raised at given instants of a run: ``--inject SIG@T`` and plant faults.

``SIG@T`` and ``SIG(value)@T`` raise the automaton input ``SIG`` at ``T`` seconds;
``ROBOT.FAULT=VALUE@T`` (``auv.leak=1@120``, ``auv.battery=5%@60``: a trailing ``%`` is
dropped, the fault's unit applies) applies the fault ``FAULT`` of robot ``ROBOT``'s plant.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Any

from orccad_app.diagnostics import OrccadError

__all__ = ["Injection", "parse_injection"]

_INJECTION = re.compile(r"^\s*([A-Za-z_][\w.]*)\s*(?:\((.*)\))?\s*@\s*([0-9.eE+-]+)\s*s?\s*$")
_FAULT = re.compile(r"^\s*([A-Za-z_]\w*\.[A-Za-z_]\w*)\s*=\s*([^@]*?)\s*@\s*([0-9.eE+-]+)\s*s?\s*$")


@dataclass(frozen=True)
class Injection:
    """An input signal raised at a simulated instant (``--inject Stop@2.5``).

    :param name: the automaton input (a mission input, or an observer event ``X.E``).
    :param time_ns: when [ns].
    :param value: its value for a valued input, else ``None``.
    :param fault: ``True`` for a plant fault ``ROBOT.FAULT=VALUE@T`` (``name`` is
        ``ROBOT.FAULT``, ``value`` the fault's value).
    """

    name: str
    time_ns: int
    value: Any = None
    fault: bool = False

    @property
    def robot_fault(self) -> tuple[str, str]:
        """A plant fault's ``(robot, fault)``."""
        robot, fault = self.name.split(".", 1)
        return robot, fault


def parse_injection(text: str) -> Injection:
    """``SIG@T``, ``SIG(value)@T`` or the plant fault ``ROBOT.FAULT=VALUE@T`` (``T`` in
    seconds, ``VALUE`` a number with an optional trailing ``%``, or true/false); raise
    :class:`OrccadError`."""
    fault = _FAULT.match(text)
    if fault is not None:
        return _fault_injection(text, *fault.groups())
    match = _INJECTION.match(text)
    if match is None:
        raise OrccadError(f"bad injection {text!r}: expected SIGNAL@SECONDS or "
                          f"SIGNAL(value)@SECONDS, e.g. Stop@2.5")
    name, raw, when = match.groups()
    try:
        seconds = float(when)
        value = None if raw is None else _value(raw.strip())
    except ValueError:
        raise OrccadError(f"bad injection {text!r}: cannot read the time or the value") from None
    if not seconds >= 0:
        raise OrccadError(f"bad injection {text!r}: the time must be >= 0 s")
    return Injection(name, int(round(seconds * 1e9)), value)


def _fault_injection(text: str, name: str, raw: str, when: str) -> Injection:
    try:
        seconds = float(when)
        value = _value(raw[:-1].strip() if raw.endswith("%") else raw)
    except ValueError:
        raise OrccadError(f"bad injection {text!r}: expected ROBOT.FAULT=VALUE@SECONDS, "
                          f"e.g. auv.leak=1@120 or auv.battery=5%@60") from None
    if not seconds >= 0:
        raise OrccadError(f"bad injection {text!r}: the time must be >= 0 s")
    return Injection(name, int(round(seconds * 1e9)), value, fault=True)


def _value(raw: str) -> Any:
    if raw in ("true", "false"):
        return raw == "true"
    try:
        return int(raw)
    except ValueError:
        return float(raw)
