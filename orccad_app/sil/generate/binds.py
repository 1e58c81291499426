"""The run-time arguments the real-time controller binds itself (issue 35 item 1).

``run GoTo(target = ?Waypoint)`` binds the Robot-Task's parameter ``target`` to the value of
the automaton output ``GoTo.arg.target`` in the instant the task starts. In ``orccad run``
the mission layer binds it in Python (:func:`~orccad_app.robottask.binding.bind_arguments`:
the value checked, the control scheme instantiated with it). The controller's automaton task
does it in C when :func:`c_binds` finds how: each component of the value lands in parameter
words of the site's Module-Tasks as a **plain copy** (found by binding two other values on
fresh Python instances and reading their C layouts, :func:`~.layout.c_layout`), and the
value is checked before it is written: finite, and each component within the interval the
Robot-Task's instantiation accepts with the other components nominal (found by bisection on
the doubles, so a bound such as ``depth >= 0`` is exact). A start whose value the checks
refuse is not made: the controller's mission fails (the supervisor, replaying the reaction in
Python, ends the run ``failed`` with the located reason, as ``orccad run`` does). A check
that couples components would be the supervisor's alone: none of the shipped kinds has one.

A site whose arguments are not all such floats or vectors of floats (an int, a string, a
value the kinds transform) keeps its lifecycle with the supervisor (``PARAM`` writes).
"""

from __future__ import annotations

import math
import struct
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from orccad_app.diagnostics import OrccadError
from orccad_app.mission.plan import MissionPlan, SiteModules
from orccad_app.robottask.run_arguments import RunArgument
from orccad_app.sil.generate.layout import c_layout, same_word
from orccad_app.sil.generate.table import ModuleTable

__all__ = ["CBind", "CBindCheck", "bindable", "c_binds", "bind_lines"]

_MAX = 1.7976931348623157e308


@dataclass(frozen=True)
class CBind:
    """One parameter word a run-time argument's component is copied into at a start.

    :param site: the run site.
    :param output: the argument output (``GoTo.arg.target``).
    :param component: the value's component (0 for a float).
    :param module: the Module-Task's TCS name.
    :param offset: the parameter word.
    """

    site: int
    output: str
    component: int
    module: str
    offset: int


@dataclass(frozen=True)
class CBindCheck:
    """What the start checks of one component: finite and in ``[low, high]``."""

    site: int
    output: str
    component: int
    low: float
    high: float


class _NotInC(Exception):
    """The site's arguments stay with the supervisor."""


def _layouts(site: SiteModules, values: Mapping[str, Any]) -> dict[str, Any] | None:
    """Each Module-Task's C layout for the start binding ``values``, ``None`` if refused."""
    try:
        instance = site.bound(values)
    except OrccadError:
        return None
    return {name: c_layout(compute) for name, compute in site.fresh_computes(instance).items()}


def _nominal(site: SiteModules, argument: RunArgument) -> list[float]:
    value: Any = site.instance.params.get(argument.param)
    if hasattr(value, "tolist"):
        value = value.tolist()
    if isinstance(value, bool) or not isinstance(value, (int, float, list, tuple)):
        raise _NotInC
    items = list(value) if isinstance(value, (list, tuple)) else [value]
    if not all(isinstance(v, float) for v in items):
        raise _NotInC  # ints, nested values: their words may not be doubles of them
    return items


def _value(nominal: list[float], scalar: bool) -> Any:
    return nominal[0] if scalar else list(nominal)


def _copies(site: SiteModules, argument: RunArgument, values: dict[str, Any],
            scalar: bool) -> list[CBind]:
    """Where each component of ``argument`` is copied (see the module docstring)."""
    nominal = _nominal(site, argument)
    base = _layouts(site, values)
    assert base is not None
    found: dict[tuple[str, int], int] | None = None
    for scale, shift in ((0.75, 0.125), (1.25, 0.25)):
        probe = [v * scale + shift * (c + 1) for c, v in enumerate(nominal)]  # distinct
        layouts = _layouts(site, {**values, argument.signal: _value(probe, scalar)})
        if layouts is None:
            raise _NotInC
        copies: dict[tuple[str, int], int] = {}
        for name, layout in layouts.items():
            old = base[name]
            if (layout.kind, layout.inputs, layout.outputs) != (old.kind, old.inputs, old.outputs):
                raise _NotInC
            for at, (was, now) in enumerate(zip(old.params, layout.params)):
                if same_word(was, now):
                    continue
                matches = [c for c, v in enumerate(probe) if same_word(v, now)
                           and same_word(nominal[c], was)]
                if len(matches) != 1:
                    raise _NotInC
                copies[(name, at)] = matches[0]
        if found is not None and copies != found:
            raise _NotInC
        found = copies
    assert found is not None
    return [CBind(site.number, argument.signal, component, name, offset)
            for (name, offset), component in sorted(found.items())]


def _ordered(x: float) -> int:
    bits = struct.unpack("=q", struct.pack("=d", x))[0]
    return bits if bits >= 0 else -(bits & 0x7FFFFFFFFFFFFFFF)


def _unordered(n: int) -> float:
    bits = n if n >= 0 else (-n) | -0x8000000000000000
    return struct.unpack("=d", struct.pack("=q", bits))[0]


def _bound(accepts: Any, inside: float, outside: float) -> float:
    """The accepted value nearest ``outside`` between an accepted ``inside`` and a refused
    ``outside`` (bisection on the doubles' order)."""
    good, bad = _ordered(inside), _ordered(outside)
    while abs(bad - good) > 1:
        middle = (good + bad) // 2
        if accepts(_unordered(middle)):
            good = middle
        else:
            bad = middle
    return _unordered(good)


def _checks(site: SiteModules, argument: RunArgument, values: dict[str, Any],
            scalar: bool) -> list[CBindCheck]:
    nominal = _nominal(site, argument)
    checks = []
    for component, middle in enumerate(nominal):
        def accepts(x: float, c: int = component) -> bool:
            value = list(nominal)
            value[c] = x
            try:
                site.bound({**values, argument.signal: _value(value, scalar)})
            except OrccadError:
                return False
            return True
        low = -_MAX if accepts(-_MAX) else _bound(accepts, middle, -_MAX)
        high = _MAX if accepts(_MAX) else _bound(accepts, middle, _MAX)
        checks.append(CBindCheck(site.number, argument.signal, component, low, high))
    return checks


def _site_binds(site: SiteModules, scalars: Mapping[str, bool],
                checks: bool) -> tuple[list[CBind], list[CBindCheck]]:
    values = {arg.signal: _value(_nominal(site, arg), scalars[arg.signal])
              for arg in site.arguments}
    binds: list[CBind] = []
    found: list[CBindCheck] = []
    for argument in site.arguments:
        scalar = scalars[argument.signal]
        binds += _copies(site, argument, values, scalar)
        if checks:
            found += _checks(site, argument, values, scalar)
    return binds, found


def _scalars(site: SiteModules) -> dict[str, bool]:
    """Per argument output, whether its value is a float (else a vector of floats)."""
    found = {}
    for argument in site.arguments:
        value = site.instance.params.get(argument.param)
        found[argument.signal] = not isinstance(value, (list, tuple)) and \
            not hasattr(value, "tolist")
    return found


def bindable(plan: MissionPlan) -> frozenset[int]:
    """The run sites with run-time arguments that the controller binds itself."""
    found = set()
    for site in plan.sites:
        if not site.arguments:
            continue
        try:
            _site_binds(site, _scalars(site), checks=False)
        except _NotInC:
            continue
        found.add(site.number)
    return frozenset(found)


def c_binds(plan: MissionPlan) -> tuple[tuple[CBind, ...], tuple[CBindCheck, ...]]:
    """The words every bindable site's arguments are copied into, and the checks."""
    binds: list[CBind] = []
    checks: list[CBindCheck] = []
    for site in plan.sites:
        if not site.arguments:
            continue
        try:
            more, checked = _site_binds(site, _scalars(site), checks=True)
        except _NotInC:
            continue
        binds += more
        checks += checked
    return tuple(binds), tuple(checks)


def _double(value: float) -> str:
    if value == _MAX:
        return "DBL_MAX"
    if value == -_MAX:
        return "(-DBL_MAX)"
    return f"({value.hex()})" if value < 0 or math.copysign(1.0, value) < 0 else value.hex()


def bind_lines(binds: tuple[CBind, ...], checks: tuple[CBindCheck, ...],
               value_word: Mapping[str, int], table: ModuleTable) -> list[str]:
    """The binding header's lines of the run-time arguments the task binds; ``value_word``:
    each output's first value word in the reply."""
    rows = [f"{{{b.site}, {value_word[b.output] + b.component}, {table.index(b.module)}, "
            f"{b.offset}}}" for b in binds]
    tests = [f"{{{c.site}, {value_word[c.output] + c.component}}}" for c in checks]
    lows = [_double(c.low) for c in checks]
    highs = [_double(c.high) for c in checks]
    return [
        "/* The run-time arguments the task binds at a start (orccad_app/sil/generate/binds.py): "
        "{site, the word of the",
        " * argument's component in the reply, Module-Task, parameter word}, and the checks "
        "{site, word} with each",
        " * component's accepted [low, high] (finite too). */",
        f"#define ORC_AUTOMATON_N_BINDS {len(rows)}",
        f"#define ORC_AUTOMATON_BINDS {{{', '.join(rows) or '{-1, 0, 0, 0}'}}}",
        f"#define ORC_AUTOMATON_N_BIND_CHECKS {len(tests)}",
        f"#define ORC_AUTOMATON_BIND_CHECKS {{{', '.join(tests) or '{-1, 0}'}}}",
        f"#define ORC_AUTOMATON_BIND_LOWS {{{', '.join(lows) or '0.0'}}}",
        f"#define ORC_AUTOMATON_BIND_HIGHS {{{', '.join(highs) or '0.0'}}}",
    ]
