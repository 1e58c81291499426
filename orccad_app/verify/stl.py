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
is ``+inf``, ``previously`` at the first is ``+inf`` (rtamt's weak ``prev``). A run of one
sample follows the same rules on that one sample (``next``: ``+inf``; a window starting after
it: none).
"""

from __future__ import annotations

import functools
import math
import re
import warnings
from dataclasses import dataclass
from typing import Any, Mapping, Sequence

from orccad_app.diagnostics import OrccadError
from orccad_app.lang import ast
from orccad_app.lang.signal_types import PortSignal

__all__ = ["StlFormula", "translate", "robustness", "event_key", "Component",
           "UndefinedRobustness"]


class UndefinedRobustness(Exception):
    """The property has no robustness on this run (``reason`` says why): a division by zero,
    the square root of a negative value, an infinity minus an infinity, or an overflow of its
    arithmetic to ±inf. The run's verdict is then *undecided*; the run itself goes on."""

    def __init__(self, reason: str) -> None:
        super().__init__(reason)
        self.reason = reason

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
    operands: tuple[str, ...] = ()
    """The rtamt text of each comparison's operands (arithmetic over the port variables),
    evaluated on the samples to tell an overflow to ±inf from an infinite margin of events."""


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
        self.operands: list[str] = []
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
            if not _reads_a_port(f.left) and not _reads_a_port(f.right):
                raise OrccadError("a comparison of constants reads no signal (its robustness "
                                  "would be a constant margin): write true or false", f.loc)
            left, right = self.scalar(f.left), self.scalar(f.right)
            self.operands.extend((left, right))
            return f"({left} {_CMP[f.op]} {right})"
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


def _reads_a_port(expr: ast.SignalExpr) -> bool:
    if isinstance(expr, ast.SPort):
        return True
    if isinstance(expr, ast.SNumber):
        return False
    if isinstance(expr, ast.SNeg):
        return _reads_a_port(expr.operand)
    if isinstance(expr, ast.SCall):
        return any(_reads_a_port(arg) for arg in expr.args)
    return _reads_a_port(expr.left) or _reads_a_port(expr.right)


def translate(formula: ast.Formula, ports: Mapping[tuple[str, str], PortSignal],
              period_ns: int) -> StlFormula:
    """``formula`` in rtamt's STL over samples of period ``period_ns``; ``ports`` are its typed
    ports (:func:`~orccad_app.lang.signal_types.port_signals`). Raises a located
    :class:`OrccadError` when a time bound is not a multiple of the period."""
    writer = _Writer(ports, period_ns)
    text = writer.formula(formula)
    return StlFormula(text, writer.port_vars, writer.event_vars, period_ns,
                      tuple(writer.operands))


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
    data = {name: [float(v) for v in values] for name, values in samples.items()}
    horizon_ns = len(next(iter(data.values()))) * stl.period_ns
    spec = _parsed(_clamped(stl.text, horizon_ns), stl.period_ns, tuple(data))
    length = len(next(iter(data.values())))
    data["time"] = [k * stl.period_ns / 1e9 for k in range(length)]
    try:
        value = _evaluate(spec, data)
    except ZeroDivisionError:
        raise UndefinedRobustness("a division by zero") from None
    except ValueError as error:  # math domain error: sqrt of a negative value
        raise UndefinedRobustness(f"the square root of a negative value ({error})") from None
    except OverflowError:
        raise UndefinedRobustness("an overflow of its arithmetic") from None
    if math.isnan(value):
        raise UndefinedRobustness("a value that is not a number (an infinity minus an "
                                  "infinity, or a sample that is not a number)")
    if math.isinf(value) and _overflows(stl, data):
        raise UndefinedRobustness("an overflow of its arithmetic to ±inf")
    return value


_BOUNDS = re.compile(r"\[(\d+)ns:(\d+)ns\]")


def _clamped(text: str, horizon_ns: int) -> str:
    """``text`` with every time bound at most ``horizon_ns`` (one period past the last
    sample). The samples past it do not exist, so the value is the same — a window reaching
    past the run reads its recorded part, one starting past it reads none — but rtamt's
    buffers follow the bounds: a window as long as the one-year bound exhausted memory."""
    def clamp(match: re.Match) -> str:
        low, high = (min(int(v), horizon_ns) for v in match.groups())
        return f"[{low}ns:{high}ns]"
    return _BOUNDS.sub(clamp, text)


def _evaluate(spec: object, data: dict[str, list[float]]) -> float:
    """The robustness at time 0. A one-sample run is evaluated on its one sample (``next`` and
    windows after it see none: ``+inf`` / ``-inf`` by the rules above): rtamt 0.4's
    ``evaluate`` computes that value, then fails checking the sampling period of a trace with
    no interval between samples, so its offline interpreter is asked for the value directly
    (reading the only sample twice, as before, invented a sample the run does not have)."""
    try:
        return float(spec.evaluate(data)[0][1])  # type: ignore[attr-defined]
    except UnboundLocalError:
        if len(data["time"]) != 1:
            raise
    interpreter = spec.offline_interpreter  # type: ignore[attr-defined]
    result = interpreter.visitAst(interpreter.ast, 1)
    return float(result[len(result) - 1][0])


def _overflows(stl: StlFormula, data: Mapping[str, Sequence[float]]) -> bool:
    """Some comparison operand leaves the finite numbers on some sample although the port
    samples are finite (the operands are our translation's arithmetic: numbers, port
    variables, + - * /, abs, sqrt — never user text)."""
    import numpy as np

    arrays = {name: np.asarray(data[name], dtype=float) for name in stl.ports}
    with np.errstate(all="ignore"):
        for operand in stl.operands:
            value = eval(operand, {"__builtins__": {}, "abs": np.abs,  # noqa: S307
                                   "sqrt": np.sqrt}, arrays)
            if np.any(np.isinf(value)):
                return True
    return False
