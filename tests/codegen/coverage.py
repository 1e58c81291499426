"""Coverage-directed scripts: a search from the Python reactor for an input path to every
transition of an automaton.

Random scripts reach few transitions of a large automaton (the guards of most need a
particular state, input combination, counter value and clock). :func:`search` explores
breadth first from the initial configuration: in each configuration (the reactor's state and
data), it tries the input combinations the state's reaction tree tests (one per transition,
valued inputs with a few values each, picked near the program's constants) at a few clock
advances (none, 1 ms, and jumps past the timers' deadlines), and keeps, for every transition
first reached, the script that reached it. Configurations are deduplicated and the search is
bounded (``max_steps`` reactions), so it ends in a second or two; what it cannot reach within
the budget (or at all: guards no data can satisfy) is reported as not covered.

A transition is a leaf of a lowered reaction tree (one root-to-leaf path of
:mod:`orccad_app.reactive.automaton`): the :class:`~orccad_app.reactive.lowered.Step` a
reaction returns names it.
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass, field

from orccad_app.diagnostics import OrccadError
from orccad_app.reactive import ir
from orccad_app.reactive.automaton import Automaton, transitions
from orccad_app.reactive.lowered import ACTION, LEAF
from orccad_app.reactive.runtime import Reactor

__all__ = ["Coverage", "search", "leaves"]

#: clock advances tried at each configuration [ns] (0: the line gives no time)
ADVANCES_NS = (0, 1_000_000, 500_000_000, 2_500_000_000, 10_000_000_000, 130_000_000_000)


@dataclass
class Coverage:
    """What the search reached: a script per transition first reached, and the total."""

    total: int
    scripts: dict[int, list[str]] = field(default_factory=dict)  # leaf number -> lines
    errors: list[list[str]] = field(default_factory=list)        # scripts ending in an error
    steps: int = 0

    @property
    def reached(self) -> int:
        return len(self.scripts)


def leaves(reactor: Reactor) -> dict[int, int]:
    """``id(step)`` -> leaf number, over every lowered tree of ``reactor``."""
    found: dict[int, int] = {}
    stack = list(reactor._trees)
    while stack:
        node = stack.pop()
        tag = node[0]
        if tag == LEAF:
            found.setdefault(id(node[1]), len(found))
        elif tag == ACTION:
            stack.append(node[4])
        else:
            stack.extend(n for n in node[2:4] if n is not None)
    return found


def _snapshot(reactor: Reactor) -> tuple:
    store = reactor.store
    return (reactor.state, reactor.status, reactor.reason, reactor.instant, dict(store.vars),
            dict(store.values), store.clock_ns, dict(store.previous))


def _restore(reactor: Reactor, snap: tuple) -> None:
    store = reactor.store
    (reactor.state, reactor.status, reactor.reason, reactor.instant, variables, values,
     store.clock_ns, previous) = snap
    store.vars, store.values, store.previous = dict(variables), dict(values), dict(previous)


def _key(snap: tuple) -> tuple:
    """A configuration: state, status, and the data (times relative to the clock)."""
    state, status, reason, _instant, variables, values, clock, _previous = snap

    def relative(value):  # a deadline (a time, >= 1 ms): pending or passed
        if type(value) is int and abs(value) >= 1_000_000:
            return "pending" if value > clock else "passed"
        return value

    return (state, status, reason,
            tuple(sorted((d.name, id(d), relative(v)) for d, v in variables.items())),
            tuple(sorted((d.name, repr(v)) for d, v in values.items())))


def _text(value) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return '"' + value + '"'
    if isinstance(value, tuple):
        return "[" + ", ".join(repr(v) for v in value) + "]"
    return repr(value)


def _values(signal: ir.SignalDecl, pools: dict[str, list], sizes: dict) -> list:
    kind = signal.type
    if kind == "vector":
        size = sizes.get(signal.name, 3)
        return [tuple([0.5] * size), tuple(float(i) for i in range(size))]
    return pools.get(kind or "", [None])[:3]


def _pools(automaton: Automaton) -> dict[str, list]:
    """Values tried for valued inputs: the program's constants, and just around them."""
    numbers: set = set()
    strings: set = set()
    stack: list = [t.expr for t in automaton.data_tests]
    while stack:
        expr = stack.pop()
        if isinstance(expr, ir.Const):
            if isinstance(expr.value, str):
                strings.add(expr.value)
            elif isinstance(expr.value, (int, float)) and not isinstance(expr.value, bool):
                numbers.add(expr.value)
        elif isinstance(expr, ir.Binary):
            stack.extend((expr.left, expr.right))
        elif isinstance(expr, ir.Unary):
            stack.append(expr.operand)
    floats = sorted({float(n) + d for n in numbers for d in (0.25, -0.25)} | {0.0})
    ints = sorted({int(n) + d for n in numbers for d in (0, 1, -1)} | {0})
    return {"float": floats, "duration": floats, "int": ints, "bool": [True, False],
            "string": sorted(strings) or ["x"]}


def _candidates(automaton: Automaton, state: int, pools, sizes) -> list[dict]:
    """Input combinations to try in ``state``: one per transition's input guard."""
    found: dict[tuple, dict] = {}
    for transition in transitions(state, automaton.trees[state]):
        present = [s for s, on in transition.inputs if on]
        choices: list[dict] = [{}]
        for signal in present:
            values = _values(signal, pools, sizes) if signal.valued else [None]
            choices = [{**c, signal.name: v} for c in choices for v in values][:6]
        for choice in choices:
            found.setdefault(tuple(sorted((k, repr(v)) for k, v in choice.items())), choice)
    found.setdefault((), {})
    return list(found.values())


def _line(clock_ns: int | None, inputs: dict) -> tuple[str, int | None]:
    """The script line of an instant, and its clock as the script reader computes it."""
    parts = [] if clock_ns is None else [f"@{clock_ns / 1e9!r}"]
    parts += [name if value is None else f"{name}({_text(value)})"
              for name, value in inputs.items()]
    time_ns = None if clock_ns is None else round(float(parts[0][1:]) * 1e9)
    return " ".join(parts), time_ns


def search(automaton: Automaton, *, max_steps: int = 30_000, max_depth: int = 40,
           sizes: dict | None = None) -> Coverage:
    """Scripts reaching as many transitions of ``automaton`` as the budget allows."""
    reactor = Reactor(automaton)
    ids = leaves(reactor)
    coverage = Coverage(len(ids))
    pools = _pools(automaton)
    sizes = sizes or {}
    start = _snapshot(reactor)
    seen = {_key(start)}
    by_state = _leaves_by_state(reactor, ids)
    uncovered = {state: set(found) for state, found in by_state.items()}
    # configurations whose state still has transitions to reach are expanded first
    hot: deque = deque([(start, [])])
    cold: deque = deque()
    candidates: dict[int, list[dict]] = {}
    while (hot or cold) and coverage.steps < max_steps and coverage.reached < coverage.total:
        snap, lines = hot.popleft() if hot else cold.popleft()
        state = snap[0]
        if state not in candidates:
            candidates[state] = _candidates(automaton, state, pools, sizes)
        for inputs in candidates[state]:
            for advance in ADVANCES_NS:
                if coverage.steps >= max_steps:
                    break
                clock = None if advance == 0 and lines else snap[6] + advance
                line, time_ns = _line(clock, inputs)
                _restore(reactor, snap)
                coverage.steps += 1
                try:
                    step = reactor.step(inputs, time_ns)
                except OrccadError:
                    if len(coverage.errors) < 50:
                        coverage.errors.append(lines + [line])
                    continue
                leaf = ids.get(id(step))
                if leaf is not None and leaf not in coverage.scripts:
                    coverage.scripts[leaf] = lines + [line]
                    uncovered.get(state, set()).discard(leaf)
                after = _snapshot(reactor)
                key = _key(after)
                if key not in seen and len(lines) + 1 < max_depth:
                    seen.add(key)
                    target = hot if uncovered.get(after[0]) else cold
                    target.append((after, lines + [line]))
    return coverage


def _leaves_by_state(reactor: Reactor, ids: dict[int, int]) -> dict[int, set[int]]:
    found: dict[int, set[int]] = {}
    for state, tree in enumerate(reactor._trees):
        stack = [tree]
        while stack:
            node = stack.pop()
            tag = node[0]
            if tag == LEAF:
                found.setdefault(state, set()).add(ids[id(node[1])])
            elif tag == ACTION:
                stack.append(node[4])
            else:
                stack.extend(n for n in node[2:4] if n is not None)
    return found
