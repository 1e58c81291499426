"""Observation quotients, as AUTO computed them on Esterel automata.

Given a set of *observed* signals, each step of the model is labelled by the observed
signals present in its instant (inputs tested present, or free and chosen present; outputs
emitted); a step with none is a hidden move, ``tau``. The quotient merges states that are
*observationally equivalent* (weak bisimulation, Milner): with ``=a=>`` the weak transitions
``tau* a tau*`` (and ``=tau=>`` for ``tau*``), two states are equivalent when each one's weak
transitions are matched by the other's into equivalent states. Computed by saturation then
partition refinement; the quotient keeps the steps between classes (``tau`` ones too) and
drops the hidden moves inside a class.

Example: the hand-over between two Robot-Tasks, ``run A; run B`` observed on
``A.good_end,B.start`` is ``0 -A.good_end B.start-> 1``: the end of one and the start of the
other happen in the same instant.
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass
from itertools import product

from orccad_app.diagnostics import OrccadError
from orccad_app.verify.model import Model

__all__ = ["Quotient", "observe", "format_quotient"]

TAU = frozenset()


@dataclass(frozen=True)
class Quotient:
    """Classes of observationally equivalent model states and the steps between them."""

    observed: tuple[str, ...]
    classes: tuple[frozenset[int], ...]              # model states of each class
    edges: tuple[tuple[int, frozenset, int], ...]    # (class, label, class)
    initial: int
    ends: frozenset[int]                             # classes holding the terminated state
    model_states: int


def _labelled_steps(model: Model, observed: tuple[str, ...]) -> list[set]:
    inputs = {s.name for s in model.automaton.inputs}
    watched_inputs = [n for n in observed if n in inputs]
    edges: list[set] = [set() for _ in model.states]
    for steps in model.steps:
        for step in steps:
            guard = dict(step.path.guard) if step.path is not None else {}
            seen = {n for n in observed if n in step.emitted or guard.get(n, False)}
            free = [n for n in watched_inputs if n not in guard]
            for choice in product((False, True), repeat=len(free)):
                label = frozenset(seen | {n for n, on in zip(free, choice) if on})
                edges[step.source].add((label, step.target))
    return edges


def _tau_closure(edges: list[set]) -> list[frozenset[int]]:
    closure = []
    for start in range(len(edges)):
        seen = {start}
        queue = deque([start])
        while queue:
            state = queue.popleft()
            for label, target in edges[state]:
                if label == TAU and target not in seen:
                    seen.add(target)
                    queue.append(target)
        closure.append(frozenset(seen))
    return closure


def _weak(edges: list[set], closure: list[frozenset[int]]) -> list[set]:
    """The weak transitions ``(label, target)`` of each state."""
    weak = []
    for state in range(len(edges)):
        found = {(TAU, t) for t in closure[state]}
        for middle in closure[state]:
            for label, target in edges[middle]:
                if label != TAU:
                    found.update((label, t) for t in closure[target])
        weak.append(found)
    return weak


def _refine(weak: list[set]) -> list[int]:
    block = [0] * len(weak)
    count = 1
    while True:
        signatures: dict[tuple, int] = {}
        new = []
        for state, moves in enumerate(weak):
            key = (block[state], frozenset((label, block[t]) for label, t in moves))
            new.append(signatures.setdefault(key, len(signatures)))
        if len(signatures) == count:
            return new
        block, count = new, len(signatures)


def observe(model: Model, names: list[str]) -> Quotient:
    """The quotient of ``model`` observed on the signals ``names``."""
    known = [s.name for s in (*model.automaton.inputs, *model.automaton.outputs)
             if not s.name.startswith("_")]
    unknown = [n for n in names if n not in known]
    if unknown:
        raise OrccadError(f"--observe: no signal {', '.join(unknown)} in mission "
                          f"{model.automaton.name} (signals: {', '.join(known)})")
    observed = tuple(dict.fromkeys(names))
    edges = _labelled_steps(model, observed)
    block = _refine(_weak(edges, _tau_closure(edges)))
    order: dict[int, int] = {}
    for state in range(len(block)):  # number classes in order of their first state
        order.setdefault(block[state], len(order))
    number = [order[b] for b in block]
    classes = [set() for _ in order]
    for state, c in enumerate(number):
        classes[c].add(state)
    moves = sorted({(number[s], label, number[t]) for s in range(len(edges))
                    for label, t in edges[s] if label != TAU or number[s] != number[t]},
                   key=lambda e: (e[0], sorted(e[1]), e[2]))
    ends = frozenset(number[s] for s in range(len(block)) if model.is_end(s))
    return Quotient(observed, tuple(frozenset(c) for c in classes), tuple(moves), number[0],
                    ends, len(model.states))


def format_quotient(quotient: Quotient, mission: str) -> str:
    """The quotient as text, one class per paragraph."""
    lines = [f"observation of {mission} on {', '.join(quotient.observed)}: "
             f"{len(quotient.classes)} classes (model: {quotient.model_states} states)"]
    for c in range(len(quotient.classes)):
        notes = [n for n, on in (("initial", c == quotient.initial), ("end", c in quotient.ends))
                 if on]
        lines.append(f"class {c}" + (f" ({', '.join(notes)})" if notes else ""))
        for source, label, target in quotient.edges:
            if source == c:
                text = " ".join(n for n in quotient.observed if n in label) or "tau"
                lines.append(f"  {text} -> {target}")
    return "\n".join(lines)
