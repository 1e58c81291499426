"""``orccad check`` on the symbolic model: the built-in properties, then each ``property``
under the ``assume`` declarations and environment fairness — the explicit checker's verdicts
(:mod:`orccad_app.verify.checker`), computed on the mission's circuit.

Every counterexample found symbolically is turned into explicit steps (:mod:`.witness`),
re-checked with the reference semantics (:mod:`orccad_app.verify.lasso`) and written as the
same replayable script as the explicit checker's.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

from orccad_app.diagnostics import OrccadError
from orccad_app.lang import ast
from orccad_app.reactive import ir
from orccad_app.reactive.circuit_data import WIDTH
from orccad_app.verify import data
from orccad_app.robottask.atoms import ACTIVE, SIGNAL, STATUS, TRUE_ATOM, Atoms
from orccad_app.robottask.composition import Composition
from orccad_app.robottask.labels import RtLabel
from orccad_app.verify.builtins import BUILTINS
from orccad_app.verify.counterexample import Script, make_script
from orccad_app.verify.formula import F, atoms, conj, from_ast, neg
from orccad_app.verify.lasso import holds_on_lasso
from orccad_app.verify.search import Instant, Lasso
from orccad_app.reactive.bdd import Node
from orccad_app.verify.symbolic.builtins import check_builtin_symbolic
from orccad_app.reactive.circuit_build import build_circuit
from orccad_app.verify.symbolic.ltl import SymbolicLasso, find_lasso_symbolic
from orccad_app.verify.symbolic.model import (MAX_COUNTER_IMAGES, SymbolicBudgetExceeded,
                                              SymbolicModel)
from orccad_app.verify.symbolic.runs import holds_at
from orccad_app.verify.symbolic.witness import Witness

__all__ = ["SymbolicCheck", "symbolic_model", "builtin_outcome", "property_outcome", "release",
           "parallel_tasks", "counters_of"]


@dataclass(frozen=True)
class SymbolicCheck:
    """What the symbolic checker explored: the sizes a report prints."""

    control_states: int
    states: int
    bdd_nodes: int
    registers: int
    walks: int
    abstracted: str | None
    """Why the counters are abstracted (None: tracked exactly, or none)."""


def symbolic_model(composition: Composition) -> tuple[SymbolicModel, Witness, SymbolicCheck]:
    """The explored symbolic model of ``composition`` (built with a lazy automaton): counters
    exact unless one leaves its bits or they take more than :data:`MAX_COUNTER_IMAGES`
    instants to explore."""
    prep = composition.automaton.prep  # type: ignore[union-attr]
    tracked = counters_of(composition)
    abstracted = None
    model = None
    if tracked:
        model = SymbolicModel(composition, build_circuit(prep, tracked=tracked))
        try:
            reachable = model.explore(MAX_COUNTER_IMAGES)
            circuit = model.circuit
            if (circuit.overflow & reachable & circuit.relations) != model.m.false:
                low, high = -(1 << (WIDTH - 1)), (1 << (WIDTH - 1)) - 1
                abstracted = f"a counter leaves [{low}, {high}]"
        except SymbolicBudgetExceeded:
            abstracted = f"the counters take more than {MAX_COUNTER_IMAGES} instants to explore"
        if abstracted is not None:
            model.m.release(model.circuit, model)
            model = None
    try:
        if model is None:
            model = SymbolicModel(composition, build_circuit(prep))
            reachable = model.explore()
        model.check_constructive()
    except BaseException:
        if model is not None:
            model.m.release(model.circuit, model)
        raise
    m = model.m
    counter_bits = [r for r in model.cur if r.startswith("v")]
    control = m.exists(["failed_before"] + counter_bits, reachable)
    sizes = SymbolicCheck(model.count(control) >> (1 + len(counter_bits)),
                          model.count(reachable), len(m.bdd), len(model.cur),
                          model.circuit.walks, abstracted)
    return model, Witness(model), sizes


def release(model: SymbolicModel, witness: Witness) -> None:
    """Free the BDDs of a finished check (the report keeps none)."""
    witness.symbolic = None  # type: ignore[assignment]
    circuit = model.circuit
    manager = model.m
    manager.release(circuit, model)


def counters_of(composition: Composition) -> tuple:
    """The variables the explicit model would track exactly (see :mod:`..data`)."""
    prep = composition.automaton.prep  # type: ignore[union-attr]
    actions = []
    stack = [prep.root]
    while stack:
        node = stack.pop()
        if isinstance(node.src, ir.Assign):
            actions.append(node.src)
        stack.extend(node.children)
    order = {a.var: None for a in actions}
    tracked = set(order)
    changed = True
    while changed:
        changed = False
        for action in actions:
            if action.var in tracked and not data.is_exact(action.expr, tracked):
                tracked.discard(action.var)
                changed = True
    return tuple(v for v in order if v in tracked)


def parallel_tasks(composition: Composition) -> str:
    """Why the symbolic engine suits ``composition`` (empty if it does not): a ``par`` with
    Robot-Tasks in two of its branches makes the explicit automaton the product of what each
    branch tests."""
    prep = composition.automaton.prep  # type: ignore[union-attr]
    regions = [(lo, hi) for label, lo, hi in prep.marks if isinstance(label, RtLabel)]

    def has_task(node) -> bool:
        return any(node.lo <= lo and hi <= node.hi for lo, hi in regions)

    stack = [prep.root]
    while stack:
        node = stack.pop()
        if isinstance(node.src, ir.Par) and sum(map(has_task, node.children)) >= 2:
            return f"Robot-Tasks in parallel at {node.src.loc}"
        stack.extend(node.children)
    return ""


def builtin_outcome(model: SymbolicModel, witness: Witness, name: str, outcome_type):
    started = time.perf_counter()
    violation = check_builtin_symbolic(model, witness, name)
    if violation is None:
        return outcome_type("built-in", name, True, seconds=time.perf_counter() - started)
    steps = violation.steps
    script = make_script(witness.model, steps, [()] * len(steps), None)
    return outcome_type("built-in", name, False, violation.message, script,
                        time.perf_counter() - started)


def _atoms(model: SymbolicModel, keys) -> dict[tuple, Node]:
    meaning = Atoms(model.composition.roles, keys)
    m = model.m
    found: dict[tuple, Node] = {}
    for key in meaning.keys:
        kind = key[0]
        if kind == TRUE_ATOM:
            found[key] = m.true
        elif kind == ACTIVE:
            found[key] = model.active(key[1])
        elif kind == STATUS:
            found[key] = model.status(key[1])
        else:
            signal = meaning.signal(key)
            found[key] = m.false if signal is None else (
                model.signal(signal) if kind == SIGNAL else model.output(signal))
    return found


class _Letters:
    """The letters of symbolic instants are already sets of atoms."""

    @staticmethod
    def letter_set(letter: frozenset) -> frozenset:
        return letter


def _instants(model: SymbolicModel, witness: Witness, points, atom_nodes: dict[tuple, Node]
              ) -> tuple[Instant, ...]:
    mentioned = {key[1] for key in atom_nodes if key[0] == SIGNAL}
    out = []
    for point in points:
        step, free = witness.step(point)
        letter = frozenset(key for key, node in atom_nodes.items() if holds_at(model, node, point))
        chosen = tuple(d.name for d in free if d.name in mentioned)
        out.append(Instant(step, chosen, letter))  # type: ignore[arg-type]
    return tuple(out)


def property_outcome(model: SymbolicModel, witness: Witness, prop: ast.Property,
                     assumptions: list[F], outcome_type, script_of):
    """The verdict on ``prop``; ``script_of(model, formula, lasso, letters, assumed)`` writes
    a counterexample's script as the explicit checker does."""
    started = time.perf_counter()
    formula = from_ast(prop.formula)
    goal = neg(formula)
    for assumption in assumptions:
        goal = conj(assumption, goal)
    nodes = _atoms(model, atoms(goal) | atoms(formula))
    found: SymbolicLasso | None = find_lasso_symbolic(model, goal, nodes)
    if found is None:
        return outcome_type("property", prop.name, True, seconds=time.perf_counter() - started)
    prefix = _instants(model, witness, found.prefix, nodes)
    loop = _instants(model, witness, found.loop, nodes)
    if holds_on_lasso(formula, [i.letter for i in prefix], [i.letter for i in loop]):
        raise OrccadError(f"internal error: the symbolic counterexample to '{prop.name}' does "
                          "not violate it", prop.loc)  # pragma: no cover - a checker defect
    lasso = Lasso(prefix, loop, 0)
    script: Script = script_of(witness.model, formula, lasso, _Letters(), bool(assumptions))
    kind = "a finite run" if script.loop_start is None else "a run that loops forever"
    return outcome_type("property", prop.name, False, f"{kind} violates it", script,
                        time.perf_counter() - started)


__all__ += ["BUILTINS"]
