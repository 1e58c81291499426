"""Signal properties: the translation of a formula and its robustness on a run.

A signal property (:func:`orccad_app.lang.ast.is_signal_formula`) is translated to a tree of
:mod:`orccad_app.verify.stl_tree` (discrete time, uniform samples of period ``period_ns``) and
evaluated by :mod:`orccad_app.verify.stl_eval`, in time linear in the run and the formula,
which gives its *robustness* at time 0 (Donzé–Maler quantitative semantics; the values are
rtamt's, :mod:`orccad_app.verify.stl_rtamt`, bit for bit):

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

Finite runs: windows are evaluated over the samples that exist. ``always`` (bounded or
not) is the minimum over the recorded part of its window (``+inf`` when none: vacuously
true), ``eventually`` the maximum (``-inf`` when none: not seen); ``next`` at the last sample
is ``+inf``, ``previously`` at the first is ``+inf`` (weak next and previous). A run of one
sample follows the same rules on that one sample (``next``: ``+inf``; a window starting after
it: none).

No robustness (:class:`UndefinedRobustness`, the verdict is *undecided* with the reason): a
division by zero, the square root of a negative value or a value that is not a number on any
sample of the run, or an infinite robustness while some comparison's operand overflowed.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Mapping, Sequence

import numpy as np

from orccad_app.diagnostics import OrccadError
from orccad_app.lang import ast
from orccad_app.lang.signal_types import PortSignal
from orccad_app.verify import stl_tree as tree
from orccad_app.verify.stl_eval import evaluate
from orccad_app.verify.stl_tree import Direction, UndefinedRobustness

__all__ = ["StlFormula", "translate", "robustness", "event_key", "Component",
           "UndefinedRobustness"]

_FUTURE = {"always": Direction.FUTURE, "eventually": Direction.FUTURE,
           "historically": Direction.PAST, "once": Direction.PAST}


@dataclass(frozen=True)
class Component:
    """One scalar signal read by a property: ``robot.port[index]`` (``index`` ``None`` for a
    scalar port)."""

    robot: str
    port: str
    index: int | None = None


@dataclass(frozen=True)
class StlFormula:
    """A signal property as evaluated on runs.

    :param tree: the formula (:mod:`orccad_app.verify.stl_tree`).
    :param ports: variable -> the port component it reads.
    :param events: variable -> the event atom's key (as in
        :mod:`orccad_app.verify.letters`: ``("started", "X")``, ``("status", "done")``…;
        ``("true",)`` for the constant).
    :param period_ns: the sampling period the time bounds were written for [ns].
    """

    tree: tree.Node
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

    def bounds(self, interval: ast.Interval | None) -> tuple[int, int | None]:
        if interval is None:
            return 0, None
        low, high = (round(v * 1e9) for v in (interval.low_s, interval.high_s))
        for value, text in ((low, interval.low_s), (high, interval.high_s)):
            if value % self.period_ns:
                raise OrccadError(f"time bound {text:g} s is not a multiple of the sampling "
                                  f"period of signal properties ({self.period_ns / 1e6:g} ms: "
                                  "the mission's instant period)", interval.loc)
        return low, high

    def formula(self, f: ast.Formula) -> tree.Node:
        if isinstance(f, (ast.FSignal, ast.FPredicate, ast.FStatus)):
            key = event_key(f)
            name = self._var(key, "e")
            self.event_vars[name] = key
            return tree.Event(name)
        if isinstance(f, ast.FBool):
            name = self._var(("true",), "e")
            self.event_vars[name] = ("true",)
            return tree.Event(name) if f.value else tree.Not(tree.Event(name))
        if isinstance(f, ast.FCompare):
            if not _reads_a_port(f.left) and not _reads_a_port(f.right):
                raise OrccadError("a comparison of constants reads no signal (its robustness "
                                  "would be a constant margin): write true or false", f.loc)
            return tree.Margin(f.op, self.scalar(f.left), self.scalar(f.right))
        if isinstance(f, ast.FUnary):
            return self.unary(f)
        return self.binary(f)

    def unary(self, f: ast.FUnary) -> tree.Node:
        inner = self.formula(f.operand)
        low, high = self.bounds(f.bounds)
        if f.op == "not":
            return tree.Not(inner)
        if f.op == "next":
            return tree.Shift(Direction.FUTURE, inner)
        if f.op == "previously":
            return tree.Shift(Direction.PAST, inner)
        if f.op == "never":
            return tree.Window("always", Direction.FUTURE, tree.Not(inner), low, high)
        return tree.Window(f.op, _FUTURE[f.op], inner, low, high)

    def binary(self, f: ast.FBinary) -> tree.Node:
        left, right = self.formula(f.left), self.formula(f.right)
        if f.op in ("and", "or"):
            return tree.Junction(f.op, left, right)
        if f.op == "->":
            return tree.Junction("implies", left, right)
        if f.op == "<->":  # not rtamt's iff: -|l - r| is NaN on two infinite atoms
            return tree.Junction("and", tree.Junction("implies", left, right),
                                 tree.Junction("implies", right, left))
        low, high = self.bounds(f.bounds)
        direction = Direction.FUTURE if f.op == "until" else Direction.PAST
        return tree.Until(direction, left, right, low, high)

    def scalar(self, expr: ast.SignalExpr) -> tree.SignalTerm:
        return self.components(expr)[0]

    def components(self, expr: ast.SignalExpr) -> list[tree.SignalTerm]:
        """Each component's term (one for a scalar)."""
        if isinstance(expr, ast.SNumber):
            return [tree.Const(float(expr.value))]
        if isinstance(expr, ast.SPort):
            dim = self.ports[(expr.robot, expr.port)].dim
            if expr.index is not None or not dim:
                return [self._port(Component(expr.robot, expr.port, expr.index))]
            return [self._port(Component(expr.robot, expr.port, i)) for i in range(dim)]
        if isinstance(expr, ast.SNeg):
            return [tree.Arith("-", tree.Const(0.0), c) for c in self.components(expr.operand)]
        if isinstance(expr, ast.SCall):
            parts = self.components(expr.args[0])
            if expr.func == "norm":
                if len(parts) == 1:
                    return [tree.Call("abs", parts[0])]
                total: tree.SignalTerm = tree.Arith("*", parts[0], parts[0])
                for c in parts[1:]:
                    total = tree.Arith("+", total, tree.Arith("*", c, c))
                return [tree.Call("sqrt", total)]
            return [tree.Call(expr.func, parts[0])]
        left, right = self.components(expr.left), self.components(expr.right)
        if len(left) < len(right):
            left = left * len(right)
        elif len(right) < len(left):
            right = right * len(left)
        return [tree.Arith(expr.op, a, b) for a, b in zip(left, right)]

    def _port(self, component: Component) -> tree.Var:
        name = self._var(component, "s")
        self.port_vars[name] = component
        return tree.Var(name)


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
    """``formula`` as a tree over samples of period ``period_ns``; ``ports`` are its typed
    ports (:func:`~orccad_app.lang.signal_types.port_signals`). Raises a located
    :class:`OrccadError` when a time bound is not a multiple of the period."""
    writer = _Writer(ports, period_ns)
    node = writer.formula(formula)
    return StlFormula(node, writer.port_vars, writer.event_vars, period_ns)


def robustness(stl: StlFormula, samples: Mapping[str, Sequence[float]]) -> float:
    """The robustness at time 0 of ``stl`` on ``samples`` (variable -> one value per sample,
    every list of one length ≥ 1; events as ``±inf``). Raises :class:`UndefinedRobustness`
    when the property has no value on the run (module docstring)."""
    lengths = {len(values) for values in samples.values()}
    if len(lengths) != 1 or 0 in lengths:
        raise ValueError(f"samples of unequal or zero length: {sorted(lengths)}")
    data = {name: np.asarray(values, dtype=float) for name, values in samples.items()}
    return evaluate(stl.tree, data, stl.period_ns)
