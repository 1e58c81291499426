"""Signal properties in rtamt: the translation of a formula and its robustness on a run.

A signal property (:func:`orccad_app.lang.ast.is_signal_formula`) is written in rtamt's STL
(discrete time, uniform samples of period ``period_ns``) and evaluated by rtamt's offline
monitor, which gives its *robustness* at time 0 (Donzé–Maler quantitative semantics):

==========================  ==========================================================
``x < c``, ``x <= c``       ``c - x``  (``>``, ``>=``: ``x - c``), in the signals' unit
``not f``                   ``-ρ(f)``
``f and g``, ``f or g``     ``min``, ``max``; ``f -> g`` is ``not f or g``,
                            ``f <-> g`` is ``(f -> g) and (g -> f)``
``always[a, b] f``          ``min`` of ``ρ(f)`` over the samples in ``[t+a, t+b]``
``eventually[a, b] f``      ``max`` over the same window; unbounded: to the end of the run
``f until[a, b] g``         ``max`` over ``t' ∈ [t+a, t+b]`` of ``min(ρ(g)(t'), min ρ(f)
                            before t')``; ``once``, ``historically``, ``since``: the past
                            mirrors
``next f``, ``previously f``  the next / previous sample
==========================  ==========================================================

Event atoms (signals, ``started(X)``, ``ended(X)``, ``raised(E)``, ``active(X)``, ``done``,
``failed``, ``aborted``, ``true``, ``false``) are boolean signals with robustness ``+inf``
when true and ``-inf`` when false: no change of a signal value changes them, so a property's
robustness is finite exactly when some comparison decides it.

Finite runs: rtamt evaluates windows over the samples that exist. ``always`` (bounded or
not) is the minimum over the recorded part of its window (``+inf`` when none: vacuously
true), ``eventually`` the maximum (``-inf`` when none: not seen); ``next`` at the last sample
is ``+inf``, ``previously`` at the first is ``+inf`` (rtamt's weak ``prev``).
"""

from __future__ import annotations

import functools
import math
import warnings
from dataclasses import dataclass
from typing import Any, Mapping, Sequence

from orccad_app.diagnostics import OrccadError
from orccad_app.lang import ast
from orccad_app.lang.signal_types import PortSignal

__all__ = ["StlFormula", "translate", "robustness", "event_key", "Component"]

INF = math.inf

_TIMED = {"always": "always", "eventually": "eventually", "once": "once",
          "historically": "historically"}
_CMP = {"<": "<", "<=": "<=", ">": ">", ">=": ">="}


@dataclass(frozen=True)
class Component:
    """One scalar signal read by a property: ``robot.port[index]`` (``index`` ``None`` for a
    scalar port)."""

    robot: str
    port: str
    index: int | None = None


@dataclass(frozen=True)
class StlFormula:
    """A signal property written in rtamt's language.

    :param text: the rtamt specification.
    :param ports: rtamt variable -> the port component it reads.
    :param events: rtamt variable -> the event atom's key (as in
        :mod:`orccad_app.verify.letters`: ``("started", "X")``, ``("status", "done")``…;
        ``("true",)`` for the constant).
    :param period_ns: the sampling period the time bounds were written for [ns].
    """

    text: str
    ports: dict[str, Component]
    events: dict[str, tuple]
    period_ns: int


def event_key(formula: ast.Formula) -> tuple:
    """The letter key of an event atom (as :func:`orccad_app.verify.formula.from_ast`)."""
    if isinstance(formula, ast.FSignal):
        return ("sig", formula.name)
    if isinstance(formula, ast.FPredicate):
        return (formula.predicate, formula.argument)
    return ("status", formula.status)


class _Writer:
    def __init__(self, ports: Mapping[tuple[str, str], PortSignal], period_ns: int):
        self.ports = ports
        self.period_ns = period_ns
        self.port_vars: dict[str, Component] = {}
        self.event_vars: dict[str, tuple] = {}
        self._names: dict[object, str] = {}

    def _var(self, key: object, prefix: str) -> str:
        name = self._names.get(key)
        if name is None:
            name = self._names[key] = f"{prefix}{len(self._names)}"
        return name

    def bounds(self, interval: ast.Interval) -> str:
        low, high = (round(v * 1e9) for v in (interval.low_s, interval.high_s))
        for value, text in ((low, interval.low_s), (high, interval.high_s)):
            if value % self.period_ns:
                raise OrccadError(f"time bound {text:g} s is not a multiple of the sampling "
                                  f"period of signal properties ({self.period_ns / 1e6:g} ms: "
                                  "the mission's instant period)", interval.loc)
        return f"[{low}ns:{high}ns]"

    def formula(self, f: ast.Formula) -> str:
        if isinstance(f, (ast.FSignal, ast.FPredicate, ast.FStatus)):
            key = event_key(f)
            name = self._var(key, "e")
            self.event_vars[name] = key
            return f"({name} >= 0)"
        if isinstance(f, ast.FBool):
            name = self._var(("true",), "e")
            self.event_vars[name] = ("true",)
            return f"({name} >= 0)" if f.value else f"(not({name} >= 0))"
        if isinstance(f, ast.FCompare):
            return f"({self.scalar(f.left)} {_CMP[f.op]} {self.scalar(f.right)})"
        if isinstance(f, ast.FUnary):
            return self.unary(f)
        return self.binary(f)

    def unary(self, f: ast.FUnary) -> str:
        inner = self.formula(f.operand)
        bounds = "" if f.bounds is None else self.bounds(f.bounds)
        if f.op == "not":
            return f"(not{inner})"
        if f.op == "next":
            return f"(next{inner})"
        if f.op == "previously":
            return f"(prev{inner})"
        if f.op == "never":
            return f"(always{bounds}(not{inner}))"
        return f"({_TIMED[f.op]}{bounds}{inner})"

    def binary(self, f: ast.FBinary) -> str:
        left, right = self.formula(f.left), self.formula(f.right)
        if f.op in ("and", "or"):
            return f"({left} {f.op} {right})"
        if f.op == "->":
            return f"({left} implies {right})"
        if f.op == "<->":  # not rtamt's iff: -|l - r| is NaN on two infinite atoms
            return f"(({left} implies {right}) and ({right} implies {left}))"
        bounds = "" if f.bounds is None else self.bounds(f.bounds)
        return f"({left} {f.op}{bounds} {right})"

    def scalar(self, expr: ast.SignalExpr) -> str:
        return self.components(expr)[0]

    def components(self, expr: ast.SignalExpr) -> list[str]:
        """The rtamt text of each component (one for a scalar)."""
        if isinstance(expr, ast.SNumber):
            return [repr(float(expr.value))]
        if isinstance(expr, ast.SPort):
            dim = self.ports[(expr.robot, expr.port)].dim
            if expr.index is not None or not dim:
                return [self._port(Component(expr.robot, expr.port, expr.index))]
            return [self._port(Component(expr.robot, expr.port, i)) for i in range(dim)]
        if isinstance(expr, ast.SNeg):
            return [f"(0 - {c})" for c in self.components(expr.operand)]
        if isinstance(expr, ast.SCall):
            parts = self.components(expr.args[0])
            if expr.func == "norm":
                if len(parts) == 1:
                    return [f"abs({parts[0]})"]
                return ["sqrt(" + " + ".join(f"{c} * {c}" for c in parts) + ")"]
            return [f"{expr.func}({parts[0]})"]
        left, right = self.components(expr.left), self.components(expr.right)
        if len(left) < len(right):
            left = left * len(right)
        elif len(right) < len(left):
            right = right * len(left)
        return [f"({a} {expr.op} {b})" for a, b in zip(left, right)]

    def _port(self, component: Component) -> str:
        name = self._var(component, "s")
        self.port_vars[name] = component
        return name


def translate(formula: ast.Formula, ports: Mapping[tuple[str, str], PortSignal],
              period_ns: int) -> StlFormula:
    """``formula`` in rtamt's STL over samples of period ``period_ns``; ``ports`` are its typed
    ports (:func:`~orccad_app.lang.signal_types.port_signals`). Raises a located
    :class:`OrccadError` when a time bound is not a multiple of the period."""
    writer = _Writer(ports, period_ns)
    text = writer.formula(formula)
    return StlFormula(text, writer.port_vars, writer.event_vars, period_ns)


@functools.lru_cache(maxsize=64)
def _parsed(text: str, period_ns: int, names: tuple[str, ...]) -> Any:
    """rtamt's parsed specification of ``text`` over the variables ``names``, parsed once per
    process and reused (a campaign's worker judges the same properties on every run):
    parsing costs some 20 ms of ANTLR per formula, more than judging a short run. rtamt's
    offline evaluation sets every variable from its dataset and recomputes every node, so a
    reused specification gives what a fresh one gives
    (``tests/verify/test_stl.py::test_a_reused_specification_equals_a_fresh_one``)."""
    with warnings.catch_warnings():  # antlr4 4.7 imports typing.io (deprecated)
        warnings.simplefilter("ignore", DeprecationWarning)
        import rtamt

    spec = rtamt.StlDiscreteTimeSpecification()
    for name in names:
        spec.declare_var(name, "float")
    spec.spec = text
    spec.set_sampling_period(period_ns, "ns", 0.1)
    try:
        spec.parse()
    except rtamt.RTAMTException as error:  # pragma: no cover - a translation defect
        raise OrccadError(f"internal error: rtamt rejects {text!r}: {error}") from None
    return spec


def robustness(stl: StlFormula, samples: Mapping[str, Sequence[float]]) -> float:
    """The robustness at time 0 of ``stl`` on ``samples`` (rtamt variable -> one value per
    sample, every list of one length ≥ 1; events as ``±inf``)."""
    lengths = {len(values) for values in samples.values()}
    if len(lengths) != 1 or 0 in lengths:
        raise ValueError(f"samples of unequal or zero length: {sorted(lengths)}")
    count = lengths.pop()
    data = {name: [float(v) for v in values] for name, values in samples.items()}
    if count == 1:  # rtamt needs two samples; the run's only state holds one period more
        data = {name: values * 2 for name, values in data.items()}
    spec = _parsed(stl.text, stl.period_ns, tuple(data))
    length = len(next(iter(data.values())))
    data["time"] = [k * stl.period_ns / 1e9 for k in range(length)]
    return float(spec.evaluate(data)[0][1])
