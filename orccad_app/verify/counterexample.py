"""Counterexamples as input scripts that ``orccad react --composed`` replays.

A counterexample is a list of model steps (and, for a liveness property, the loop that
repeats forever). Turning it into a script means choosing, for each instant:

- the inputs present: those the step's guard tests true, plus the free inputs the search
  took present;
- the clock, when timers matter: the path's timer tests are collected by a symbolic run
  (a deadline is ``clock_k + c``, the clock of instant ``k`` plus a constant) as difference
  constraints ``clock_j - clock_k >= c`` or ``<= c - 1`` (nanoseconds), with the clock never
  decreasing; Bellman–Ford gives the times, or shows the path cannot be timed;
- a value for each valued input, tried among the program's constants (and ±1) until the
  reaction takes the step's path.

The script is then replayed on the composed automaton (:class:`~orccad_app.reactive.runtime.Reactor`)
and ``replayed`` says whether every instant reached the state the counterexample says.
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import product
from typing import Any, Sequence

from orccad_app.reactive import ir
from orccad_app.reactive.labels import InMission, in_missions
from orccad_app.reactive.runtime import Reactor
from orccad_app.verify.data import TOP, is_clock_test
from orccad_app.verify.model import Model, Step

__all__ = ["Line", "Script", "make_script"]

_CMP = ("<", "<=", ">", ">=", "==")
_NEGATE = {"<": ">=", "<=": ">", ">": "<=", ">=": "<", "==": "!="}


@dataclass(frozen=True)
class Line:
    """One instant of a script: the clock (ns, or None) and the inputs with their values;
    ``inside``: the sub-mission instances the mission is in after it."""

    time_ns: int | None
    inputs: tuple[tuple[str, Any], ...]
    inside: tuple[InMission, ...] = ()

    def text(self) -> str:
        """The instant as ``orccad react`` reads it."""
        parts = [] if self.time_ns is None else [f"@{_seconds(self.time_ns)}"]
        parts += [name if value is None else f"{name}({_literal(value)})"
                  for name, value in self.inputs]
        return " ".join(parts)


@dataclass(frozen=True)
class Script:
    """A replayable counterexample: ``lines``, of which those from ``loop_start`` on repeat
    forever (None: a finite trace whose last instant shows the violation). Its text says, in
    a comment line after each instant that changes it, which sub-mission instances the
    mission is in (``# in Homing#2 (lib/homing.orc:8) inside arm_recovery.orc:54, …``)."""

    lines: tuple[Line, ...]
    loop_start: int | None
    replayed: bool
    note: str = ""

    def text(self, header: Sequence[str] = ()) -> str:
        out = [f"# {h}" for h in header]
        inside: tuple[InMission, ...] = ()
        for number, line in enumerate(self.lines):
            if number == self.loop_start:
                out.append("# loop: the following instants repeat forever"
                           + (" (times shifted by the loop's duration)"
                              if line.time_ns is not None else ""))
            out.append(line.text())
            if line.inside != inside:  # a comment line (not an instant) when it changes
                inside = line.inside
                out.append(f"# in {'; in '.join(i.text() for i in inside)}" if inside
                           else "# out of the sub-missions")
        return "\n".join(out) + "\n"


def _seconds(ns: int) -> str:
    text = f"{ns / 1e9:.9f}".rstrip("0").rstrip(".")
    return text or "0"


def _literal(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return f'"{value}"'
    if isinstance(value, tuple):
        return "[" + ", ".join(repr(float(v)) for v in value) + "]"
    return repr(value)


# --------------------------------------------------------------------------- timing

def _symbolic(expr: ir.Expr, env: dict, instant: int):
    """``("clk", k, c)`` for clock_k + c, a number, or TOP."""
    if isinstance(expr, ir.Clock):
        return ("clk", instant, 0)
    if isinstance(expr, ir.Const):
        return expr.value if isinstance(expr.value, (int, float)) else TOP
    if isinstance(expr, ir.VarRef):
        return env.get(expr.var, TOP)
    if isinstance(expr, ir.Binary) and expr.op in ("+", "-"):
        left, right = _symbolic(expr.left, env, instant), _symbolic(expr.right, env, instant)
        sign = 1 if expr.op == "+" else -1
        if isinstance(left, tuple) and isinstance(right, (int, float)):
            return ("clk", left[1], left[2] + sign * right)
        if isinstance(right, tuple) and isinstance(left, (int, float)) and sign == 1:
            return ("clk", right[1], right[2] + left)
        if isinstance(left, (int, float)) and isinstance(right, (int, float)):
            return left + sign * right
    return TOP


def _constraint(expr: ir.Expr, outcome: bool, env: dict, instant: int) -> list[tuple]:
    """Difference constraints ``(a, b, w)``: clock_a - clock_b <= w (``"z"`` is time 0)."""
    if not (isinstance(expr, ir.Binary) and expr.op in _CMP):
        return []
    left, right = _symbolic(expr.left, env, instant), _symbolic(expr.right, env, instant)
    op = expr.op if outcome else _NEGATE[expr.op]
    terms = []
    for side in (left, right):
        if isinstance(side, tuple):
            terms.append((side[1], side[2]))
        elif isinstance(side, (int, float)) and not isinstance(side, bool):
            terms.append(("z", side))
        else:
            return []
    (a, ca), (b, cb) = terms
    if a == "z" and b == "z":
        return []
    w = cb - ca  # clock_a - clock_b  op  w
    if op == "<=":
        return [(a, b, w)]
    if op == "<":
        return [(a, b, w - 1)]
    if op == ">=":
        return [(b, a, -w)]
    if op == ">":
        return [(b, a, -w - 1)]
    if op == "==":
        return [(a, b, w), (b, a, -w)]
    return []


def _times(model: Model, steps: Sequence[Step]) -> list[int] | None:
    """Clock values making the path's timer tests come out as in the path, or None."""
    tests = model.automaton.data_tests
    constraints: list[tuple] = [("z", 0, 0)]
    env: dict = {}
    for j, step in enumerate(steps):
        if j:
            constraints.append((j - 1, j, 0))
        for event in step.path.events if step.path is not None else ():
            if event[0] == "act" and event[1].kind == "assign":
                env[event[1].target] = _symbolic(event[1].expr, env, j)
            elif event[0] == "test":
                constraints += _constraint(tests[event[1]].expr, event[2], env, j)
    nodes = ["z", *range(len(steps))]
    distance = {n: 0 for n in nodes}
    for _ in range(len(nodes)):
        changed = False
        for a, b, w in constraints:
            if distance[b] + w < distance[a]:
                distance[a] = distance[b] + w
                changed = True
        if not changed:
            return [int(round(distance[j] - distance["z"])) for j in range(len(steps))]
    return None


# --------------------------------------------------------------------------- values

def _candidates(model: Model, signal: ir.SignalDecl) -> list[Any]:
    if signal.type == "bool":
        return [True, False]
    if signal.type == "string":
        return [""]
    if signal.type == "vector":
        return [(0.0, 0.0, 0.0)]
    constants = {0}
    for test in model.automaton.data_tests:
        stack = [test.expr]
        while stack:
            expr = stack.pop()
            if isinstance(expr, ir.Const) and isinstance(expr.value, (int, float)) \
                    and not isinstance(expr.value, bool):
                constants.add(expr.value)
            elif isinstance(expr, (ir.Binary,)):
                stack += [expr.left, expr.right]
            elif isinstance(expr, ir.Unary):
                stack.append(expr.operand)
    values = sorted({v + d for v in constants for d in (0, 1, -1)})
    return [int(v) for v in values] if signal.type == "int" else [float(v) for v in values]


def _snapshot(reactor: Reactor) -> tuple:
    store = reactor.store
    return (reactor.state, dict(store.vars), dict(store.values), store.clock_ns,
            reactor.status, reactor.reason, reactor.instant)


def _restore(reactor: Reactor, saved: tuple) -> None:
    (reactor.state, variables, values, clock, reactor.status, reactor.reason,
     reactor.instant) = saved
    reactor.store.vars, reactor.store.values = dict(variables), dict(values)
    reactor.store.clock_ns = clock


def _react(model: Model, reactor: Reactor, step: Step, present: list[str],
           clock: int | None) -> tuple[tuple, bool]:
    """React one instant, choosing valued inputs' values; ``(inputs, followed)``."""
    decls = {s.name: s for s in model.automaton.inputs}
    valued = [n for n in present if decls[n].valued]
    options = [_candidates(model, decls[n]) for n in valued]
    saved = _snapshot(reactor)
    first = None
    for count, choice in enumerate(product(*options)):
        if count >= 256:
            break
        inputs = {n: dict(zip(valued, choice)).get(n) for n in present}
        _restore(reactor, saved)
        try:
            reaction = reactor.react(inputs, clock)
        except Exception:  # noqa: BLE001 - a run-time data error: try another value
            continue
        first = first or inputs
        expected = model.control(step.target)
        if reaction.state == expected and set(reaction.outputs) == set(step.emitted):
            return tuple(inputs.items()), True
    if first is None:
        first = {n: None for n in present}
    return tuple(first.items()), False


def _inside(model: Model, step: Step) -> tuple[InMission, ...]:
    """Where the mission is after ``step``: its sub-mission instances (and their statements
    the state waits at)."""
    labels = model.labels(step.target)
    if not labels:
        return ()
    return in_missions(labels, model.automaton.waiting[model.control(step.target)])


def make_script(model: Model, steps: Sequence[Step], chosen: Sequence[tuple[str, ...]],
                loop_start: int | None) -> Script:
    """The script of the run ``steps`` (free inputs ``chosen`` present), replayed."""
    tests = model.automaton.data_tests
    timed = any(e[0] == "test" and is_clock_test(tests[e[1]].expr)
                for s in steps if s.path is not None for e in s.path.events)
    times = _times(model, steps) if timed else None
    note = "" if times is not None or not timed else \
        "the timers of this run cannot all be met (timers are abstracted in the model)"
    reactor = Reactor(model.automaton)
    lines, followed = [], True
    for j, (step, extra) in enumerate(zip(steps, chosen)):
        guard = step.path.guard if step.path is not None else ()
        present = [n for n, on in guard if on] + list(extra)
        clock = times[j] if times is not None else None
        inputs, ok = _react(model, reactor, step, present, clock)
        followed = followed and ok
        lines.append(Line(clock, inputs, _inside(model, step)))
    if not followed and not note:
        note = "the replay leaves the counterexample (data values the model abstracts)"
    return Script(tuple(lines), loop_start, followed, note)

