"""The type-1 updates the real-time controller applies itself (RR-1801 §3.4.2).

When the automaton task (``orccad_rt_automaton.c``) reacts with ``X.E.adjust``, it applies E's
update to the running Module-Task's parameter words in that reaction, as
:class:`~orccad_app.mission.updates.TypeOneUpdates` does in ``orccad run``, for the updates
:func:`c_adjustments` finds it can apply alone:

- a **constant** (``adjust ctrl.kp = 200.0``): the parameter words the value gives, found by
  setting it on a fresh Python instance and reading its C layout;
- a **computed** value (``min(ctrl.kp * 1.5, kmax)``) and a **ramp** with computed ends
  (``ramp(0.0, 20.0, 1 s)``) of a ``float`` parameter whose words are copies of its value (a
  gain broadcast to the joints): the expression becomes C over the current parameter words of
  the Module-Tasks it reads (:func:`c_expression`, numpy's semantics: ``min``/``max`` propagate
  NaN, ``clip`` refuses swapped bounds), the value is checked against the parameter's declared
  range and finiteness before it is written (a refused value is not written: the supervisor,
  replaying the reaction in Python, ends the run ``failed`` with the located reason); a ramp
  is stepped at each release of its (periodic) Module-Task from the update to its end, the
  value interpolated at the release instant as the executive computes it (a sporadic
  Module-Task's: at the last step of the executive's grid, every minimum inter-arrival from
  the update, before the release).

An update is the controller's only if every update of each parameter it writes or reads is
the controller's too (otherwise the supervisor's writes and the controller's would race):
its words are then the controller's alone (:attr:`CAdjust.offsets`), and the supervisor's
proxies never send them (:class:`~orccad_app.sil.controller.remote.RemoteModule`'s ``c_owned``). The
rest — a vector computed value, a parameter read or written by an update the controller
cannot apply, a site whose run-time arguments the controller does not bind — stays with
the supervisor (``PARAM`` requests).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from enum import IntEnum
from typing import Any

import numpy as np

from orccad_app.lang import ast
from orccad_app.mission.plan import MissionPlan, ParamUpdate, SiteModules
from orccad_app.robottask.signals import RoleKind
from orccad_app.sil.generate.table import ModuleTable
from orccad_app.sil.generate.layout import c_layout, same_word

__all__ = ["AdjustForm", "CAdjust", "adjust_lines", "c_adjustments", "c_expression",
           "c_owned_words"]

_EXACT_INT = 2 ** 53
"""Integers beyond this are not exact as doubles: such a task parameter stays in Python."""


class AdjustForm(IntEnum):
    """How the automaton task computes an update's value (``ORC_AUTOMATON_ADJUSTS``)."""

    CONSTANT = 0
    """Fixed words, written as they are."""
    COMPUTED = 1
    """An expression over the current parameter words, computed in the reaction."""
    RAMP = 2
    """A ramp: its ends computed in the reaction, stepped at the Module-Task's releases."""


@dataclass(frozen=True)
class CAdjust:
    """A type-1 update the real-time automaton task applies itself.

    :param site: the run site's number.
    :param exception: the type-1 exception.
    :param module: the Module-Task's index in the table.
    :param signal: the automaton output that applies it (``X.E.adjust``).
    :param form: constant, computed or ramp.
    :param words: :attr:`AdjustForm.CONSTANT`: ``(offset, value)`` of each parameter word
        the update changes in the C layout; otherwise the words that copy the parameter's
        value, with its nominal value.
    :param values: the C expressions of the value, or of the ramp's start and end.
    :param duration_ns: the ramp's duration [ns] (0: no ramp).
    :param check: the C condition on ``v`` that the parameter's declaration puts on a value.
    """

    site: int
    exception: str
    module: int
    signal: str
    form: AdjustForm
    words: tuple[tuple[int, float], ...]
    values: tuple[str, ...] = ()
    duration_ns: int = 0
    check: str = "1"

    @property
    def offsets(self) -> tuple[int, ...]:
        """The parameter words it writes."""
        return tuple(at for at, _ in self.words)


class _NotInC(Exception):
    """The update stays with the supervisor."""


@dataclass(frozen=True)
class _Candidate:
    adjust: CAdjust
    writes: tuple[str, str]
    reads: tuple[tuple[str, str], ...]


def c_adjustments(plan: MissionPlan, table: ModuleTable,
                  managed: frozenset[int]) -> tuple[CAdjust, ...]:
    """The type-1 updates of the ``managed`` sites (those whose lifecycle the automaton task
    applies) that the task applies too (see the module docstring); the others are the
    supervisor's."""
    found: list[CAdjust] = []
    for site in plan.sites:
        if site.number not in managed:
            continue
        candidates: dict[str, _Candidate] = {}
        for exception, update in site.adjustments.items():
            signal = next((name for name, role in plan.roles.by_signal.items()
                           if role.kind is RoleKind.ADJUST and role.task == site.task
                           and role.name == exception), None)
            if signal is None:
                continue
            try:
                candidates[exception] = _candidate(plan, site, exception, update, signal, table)
            except _NotInC:
                continue
        found += [c.adjust for c in _closed(site, candidates).values()]
    return tuple(found)


def c_owned_words(adjusts: tuple[CAdjust, ...], table: ModuleTable) -> dict[str, frozenset[int]]:
    """Per Module-Task (TCS name), the parameter words only the automaton task writes."""
    owned: dict[str, set[int]] = {}
    for adjust in adjusts:
        owned.setdefault(table.entries[adjust.module].name, set()).update(adjust.offsets)
    return {name: frozenset(words) for name, words in owned.items()}


def _closed(site: SiteModules, candidates: dict[str, _Candidate]) -> dict[str, _Candidate]:
    """The candidates whose written and read parameters no update of the supervisor's
    changes (dropping one may drop others: until nothing changes)."""
    kept = dict(candidates)
    while True:
        theirs = {(u.module, u.param) for e, u in site.adjustments.items() if e not in kept}
        dropped = [e for e, c in kept.items()
                   if c.writes in theirs or any(read in theirs for read in c.reads)]
        if not dropped:
            return kept
        for exception in dropped:
            del kept[exception]


def _candidate(plan: MissionPlan, site: SiteModules, exception: str, update: ParamUpdate,
               signal: str, table: ModuleTable) -> _Candidate:
    module = table.index(update.module)
    form = update.form
    if form is None or (form.ramp is None and form.constant):
        words = _constant_words(site, update)
        return _Candidate(CAdjust(site.number, exception, module, signal, AdjustForm.CONSTANT,
                                  words), (update.module, update.param), ())
    fresh = _fresh(site, update.module)
    spec = fresh.param_spec(update.param)
    if "float" not in spec.type.split("|"):  # a gain: "float|vector", a float here
        raise _NotInC
    words = _copy_words(site, update.module, update.param)
    reads: list[tuple[str, str]] = []

    def read(local: str, param: str) -> str:
        name = update.modules.get(local)
        if name is None:
            raise _NotInC
        offsets = _copy_words(site, name, param)
        reads.append((name, param))
        return f"orc_rt_get_param({table.index(name)}, {offsets[0][0]})"

    values = tuple(c_expression(expr, update.env, read) for expr in form.expressions)
    duration = 0
    if form.ramp is not None:  # a sporadic one: stepped every minimum inter-arrival (the C
        duration = form.ramp.duration_ns  # floors each release onto that grid)
    return _Candidate(CAdjust(site.number, exception, module, signal,
                              AdjustForm.RAMP if duration else AdjustForm.COMPUTED, words,
                              values, duration, _range_check(spec)),
                      (update.module, update.param), tuple(reads))


def _fresh(site: SiteModules, module: str) -> Any:
    """A fresh Python instance of ``module`` of ``site`` (never a controller's proxy)."""
    return SiteModules.fresh_computes(site)[module]


def _layout(instance: Any) -> tuple[float, ...]:
    return c_layout(instance).params


def _constant_words(site: SiteModules, update: ParamUpdate) -> tuple[tuple[int, float], ...]:
    """Every word that depends on the parameter, with the value the constant gives it (a
    word equal to the nominal one is written too: the parameter may hold another value when
    the update comes)."""
    module = _fresh(site, update.module)
    try:
        module.set_param(update.param, update.value)
    except Exception:  # refused: the supervisor's update fails the run, located
        raise _NotInC from None
    params = _layout(module)
    base = _layout(_fresh(site, update.module))
    dependent = {at for at, (old, new) in enumerate(zip(base, params)) if not same_word(old, new)}
    nominal = _fresh(site, update.module).get_param(update.param)
    for probe in _probes(nominal):
        instance = _fresh(site, update.module)
        try:
            instance.set_param(update.param, probe)
        except Exception:
            continue
        dependent |= {at for at, (old, new) in enumerate(zip(base, _layout(instance)))
                      if not same_word(old, new)}
    offsets = tuple(sorted(dependent))
    if not _own_words(site, update.module, update.param, offsets):
        raise _NotInC
    return tuple((at, params[at]) for at in offsets)


def _probes(nominal: Any) -> list[Any]:
    """Values other than ``nominal`` to find the words a parameter gives."""
    if isinstance(nominal, (bool, np.bool_)):
        return [not nominal]
    if isinstance(nominal, (int, float)):
        return [nominal * 0.75, nominal * 1.25, nominal + 0.5, 0.5, 2.0, nominal - 0.5]
    if isinstance(nominal, (list, tuple, np.ndarray)):
        array = np.asarray(nominal, dtype=float)
        return [array * 0.75 + 0.125, array * 1.25 + 0.25]
    return []


def _copy_words(site: SiteModules, module: str, param: str) -> tuple[tuple[int, float], ...]:
    """The words that hold ``param``'s value as it is (its nominal value with each), found
    by setting two other values on fresh instances; raises :class:`_NotInC` when the words
    are not plain copies of a float parameter or depend on another parameter too."""
    nominal = _fresh(site, module).get_param(param)
    if isinstance(nominal, bool) or not isinstance(nominal, (int, float)):
        raise _NotInC
    base = _layout(_fresh(site, module))
    found: set[int] | None = None
    probes = 0
    for probe in _probes(nominal):
        if probe == nominal:
            continue
        instance = _fresh(site, module)
        try:
            instance.set_param(param, float(probe))
        except Exception:
            continue
        params = _layout(instance)
        changed = {at for at, (old, new) in enumerate(zip(base, params)) if not same_word(old, new)}
        if not changed or any(params[at] != probe for at in changed) or \
                (found is not None and changed != found):
            raise _NotInC
        found, probes = changed, probes + 1
        if probes == 2:
            break
    if found is None or probes < 2 or any(base[at] != nominal for at in found):
        raise _NotInC
    offsets = tuple(sorted(found))
    if not _own_words(site, module, param, offsets):
        raise _NotInC
    return tuple((at, float(nominal)) for at in offsets)


def _own_words(site: SiteModules, module: str, param: str, offsets: tuple[int, ...]) -> bool:
    """The parameter words at ``offsets`` depend on ``param`` alone (each other numeric
    parameter of the Module-Task perturbed leaves them as they are): writing them keeps what
    the other parameters' updates wrote."""
    base = _layout(_fresh(site, module))
    for other, value in _fresh(site, module).params.items():
        if other == param or isinstance(value, (bool, str)):
            continue
        probe = _fresh(site, module)
        try:
            probe.set_param(other, np.asarray(value, dtype=float) * 1.5 + 0.25)
        except Exception:
            try:
                probe.set_param(other, float(value) * 1.5 + 0.25)
            except Exception:
                return False  # cannot tell: the supervisor applies it
        if any(not same_word(_layout(probe)[at], base[at]) for at in offsets):
            return False
    return True


def _literal(value: float) -> str:
    """A C99 double literal of exactly ``value`` (hexadecimal)."""
    return f"({value.hex()})" if value < 0 else value.hex()


def c_expression(expr: ast.Expr, env: Mapping[str, Any],
                 read: Callable[[str, str], str]) -> str:
    """The C of a scalar type-1 update expression (``robottask.updates.compute``'s
    semantics, in the same operations, so the same double): ``read(module, param)`` gives the
    C of a parameter's current value; raises :class:`_NotInC` for what is not a scalar."""
    if isinstance(expr, ast.Number):
        return _literal(float(expr.value))
    if isinstance(expr, ast.Name):
        value = env.get(expr.name)
        if isinstance(value, bool) or not isinstance(value, (int, float)) or \
                (isinstance(value, int) and abs(value) > _EXACT_INT):
            raise _NotInC
        return _literal(float(value))
    if isinstance(expr, ast.ParamRef):
        return read(expr.module, expr.param)
    if isinstance(expr, ast.Unary) and expr.op == "-":
        return f"(-{c_expression(expr.operand, env, read)})"
    if isinstance(expr, ast.Binary) and expr.op in ("+", "-", "*", "/"):
        return (f"({c_expression(expr.left, env, read)} {expr.op} "
                f"{c_expression(expr.right, env, read)})")
    if isinstance(expr, ast.Call) and expr.func in ("min", "max", "abs", "clip"):
        args = [c_expression(arg.value, env, read) for arg in expr.args]
        if expr.func == "abs":
            return f"fabs({args[0]})"
        if expr.func == "clip":
            return f"adjust_clip({args[0]}, {args[1]}, {args[2]}, ok)"
        folded = args[0]
        for arg in args[1:]:  # numpy's reduce: a left fold
            folded = f"adjust_{expr.func}({folded}, {arg})"
        return folded
    raise _NotInC  # a vector, a string, a boolean: the supervisor's


def _range_check(spec: Any) -> str:
    """The C condition on ``v`` of the parameter's declaration (``ParamSpec.coerce``)."""
    parts = ["isfinite(v)"]
    if spec.maximum is not None:
        parts.append(f"v <= {_literal(float(spec.maximum))}")
    if spec.minimum is not None:
        parts.append(f"v {'>' if spec.exclusive else '>='} {_literal(float(spec.minimum))}")
    return " && ".join(parts)


def adjust_lines(adjusts: tuple[CAdjust, ...], presence: Mapping[str, int]) -> list[str]:
    """The binding header's lines of the type-1 updates the task applies; ``presence``:
    each output's presence word in the reply. The rows are in the outputs' order, the order
    in which the mission layer applies a reaction's updates."""
    adjusts = tuple(sorted(adjusts, key=lambda adjust: presence[adjust.signal]))
    rows: list[str] = []
    offsets: list[str] = []
    values: list[str] = []
    computed: list[str] = []
    checks: list[str] = []
    for a, adjust in enumerate(adjusts):
        rows.append(f"{{{adjust.site}, {presence[adjust.signal]}, {adjust.module}, "
                    f"{int(adjust.form)}, {len(offsets)}, {len(adjust.words)}}}")
        offsets += [str(at) for at, _ in adjust.words]
        values += [repr(float(value)) for _, value in adjust.words]
        computed += [f"    case {2 * a + which}: return {code}; \\"
                     for which, code in enumerate(adjust.values)]
        if adjust.form is not AdjustForm.CONSTANT:
            checks.append(f"    case {a}: return {adjust.check}; \\")
    durations = [str(adjust.duration_ns) + "LL" for adjust in adjusts]
    return [
        "/* The type-1 updates the task applies (orccad_app/sil/generate/adjust.py), in output order: "
        "{site, the ADJUST",
        " * output's presence word in the reply, Module-Task, form (0 constant words, 1 "
        "computed, 2 ramp), first of its",
        " * parameter words in the two lists below, how many} (a constant's values; the "
        "nominal value of the others'),",
        " * each ramp's duration [ns], and the code of the computed values (case 2a: update "
        "a's value or its ramp's",
        " * start, 2a + 1: its ramp's end) and of the range checks on a value v (case a). */",
        f"#define ORC_AUTOMATON_N_ADJUSTS {len(rows)}",
        f"#define ORC_AUTOMATON_ADJUSTS {{{', '.join(rows) or '{0, 0, 0, 0, 0, 0}'}}}",
        f"#define ORC_AUTOMATON_ADJUST_OFFSETS {{{', '.join(offsets) or '0'}}}",
        f"#define ORC_AUTOMATON_ADJUST_VALUES {{{', '.join(values) or '0.0'}}}",
        f"#define ORC_AUTOMATON_ADJUST_DURATIONS {{{', '.join(durations) or '0LL'}}}",
        "#define ORC_AUTOMATON_ADJUST_VALUE_CASES \\", *computed, "",
        "#define ORC_AUTOMATON_ADJUST_CHECK_CASES \\", *checks, ""]
