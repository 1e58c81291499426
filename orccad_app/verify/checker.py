"""Checking a mission: the built-in properties, then each ``property`` under the ``assume``
declarations and environment fairness.

A property holds when every fair run of the model that satisfies the assumptions satisfies
it. The checker searches for a counterexample: a fair lasso of the model × the tableau of
``assumptions and not property``; a lasso found is confirmed by the reference semantics
(:mod:`.lasso`) and turned into a replayable script. For a safety property written
``always P`` (or ``never P``) with ``P`` about the present and the past, the script stops at
the first instant where ``P`` is false.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Protocol

from orccad_app.diagnostics import OrccadError
from orccad_app.lang import ast
from orccad_app.reactive.compiler import DEFAULT_MAX_STATES, TransitionBudgetExceeded
from orccad_app.verify.builtins import BUILTINS, check_builtin
from orccad_app.robottask.composition import Composition, compose
from orccad_app.verify.counterexample import Script, make_script
from orccad_app.verify.formula import F, TRUE, atoms, conj, from_ast, is_past, neg
from orccad_app.verify.lasso import Periodic, evaluate, holds_on_lasso
from orccad_app.verify.letters import Alphabet
from orccad_app.verify.model import Model, build_model
from orccad_app.verify.search import Instant, Lasso, find_lasso
from orccad_app.verify.symbolic.checker import (SymbolicCheck, builtin_outcome, counters_of,
                                                parallel_tasks, property_outcome, release,
                                                symbolic_model)
from orccad_app.verify.tableau import Tableau

__all__ = ["PropertyOutcome", "MissionReport", "check_mission", "check_formula", "applicable",
           "CheckProgress", "ENGINES", "EXPLICIT", "SYMBOLIC", "AUTO", "AUTO_EXPLICIT_TRANSITIONS"]


@dataclass
class PropertyOutcome:
    """The verdict on one property (``kind`` is ``built-in`` or ``property``)."""

    kind: str
    name: str
    holds: bool
    message: str = ""
    script: Script | None = None
    seconds: float = 0.0


@dataclass
class MissionReport:
    """Every verdict on one mission, and the sizes of what was checked.

    ``engine`` says which checker decided (:data:`EXPLICIT` or :data:`SYMBOLIC`); a symbolic
    check's ``model`` holds only the explicit steps of its counterexamples, its sizes are in
    ``symbolic``."""

    composition: Composition
    model: Model
    outcomes: list[PropertyOutcome] = field(default_factory=list)
    signal_properties: list[ast.Property] = field(default_factory=list)
    """Signal (STL) properties: not proved here, judged on runs and campaigns."""
    engine: str = "explicit"
    symbolic: SymbolicCheck | None = None
    engine_reason: str = ""
    """Why the engine was chosen (``auto``): empty when the user chose it."""

    @property
    def holds(self) -> bool:
        return all(o.holds for o in self.outcomes)

    def summary(self, data: bool = True) -> str:
        """The first line of the report: what was explored, by which engine (``data``: and
        whether the counters are exact)."""
        kind = "counters exact" if self.counters_exact else "data abstracted"
        if self.abstracted_because:
            kind += f": {self.abstracted_because}"
        tail = f" ({kind})" if data else ""
        if self.symbolic is not None:
            why = f" ({self.engine_reason})" if self.engine_reason else ""
            return (f"mission {self.composition.name}: symbolic{why}, {self.automaton_states} "
                    f"control states, model {self.model_states} states{tail}")
        return (f"mission {self.composition.name}: automaton {self.automaton_states} states, "
                f"model {self.model_states} states / {self.model_steps} steps{tail}")

    @property
    def automaton_states(self) -> int:
        """Control states: of the minimized automaton, or reachable in the circuit."""
        if self.symbolic is not None:
            return self.symbolic.control_states
        return self.composition.automaton.state_count

    @property
    def model_states(self) -> int:
        return self.symbolic.states if self.symbolic is not None else len(self.model.states)

    @property
    def model_steps(self) -> int | None:
        """Steps of the explicit model (None for a symbolic check: it has no list of steps)."""
        return None if self.symbolic is not None else self.model.step_count

    @property
    def counters_exact(self) -> bool:
        return self.model.exact if self.symbolic is None else self.symbolic.abstracted is None

    @property
    def abstracted_because(self) -> str | None:
        if self.symbolic is None:
            return self.model.abstracted_because
        return self.symbolic.abstracted


def applicable(items, mission: ast.Mission) -> list:
    """The properties (or assumptions) of the file that apply to ``mission``."""
    return [i for i in items if i.mission is None or i.mission == mission.name]


def _safety_body(f: F) -> F | None:
    """``P`` when ``f`` is ``always P`` with ``P`` a present-and-past formula."""
    if f.op == "not" and f.left.op == "U" and f.left.left == TRUE:  # type: ignore[union-attr]
        body = neg(f.left.right)  # type: ignore[union-attr]
        return body if is_past(body) else None
    return None


def check_formula(model: Model, formula: F, assumptions: list[F] = (),
                  fair: bool = True) -> tuple[Lasso | None, Alphabet]:
    """A fair run satisfying the assumptions and violating ``formula`` (or None), and the
    alphabet its letters are written in."""
    goal = neg(formula)
    for assumption in assumptions:
        goal = conj(assumption, goal)
    alphabet = Alphabet(model, atoms(goal) | atoms(formula))
    return find_lasso(model, alphabet, Tableau(goal, alphabet), fair=fair), alphabet


def _word(lasso: Lasso, alphabet: Alphabet) -> tuple[list, list]:
    return ([alphabet.letter_set(i.letter) for i in lasso.prefix],
            [alphabet.letter_set(i.letter) for i in lasso.loop])


def _instant(lasso: Lasso, position: int) -> Instant:
    if position < len(lasso.prefix):
        return lasso.prefix[position]
    return lasso.loop[(position - len(lasso.prefix)) % len(lasso.loop)]


def _script(model: Model, formula: F, lasso: Lasso, alphabet: Alphabet,
            assumed: bool) -> Script:
    body = None if assumed else _safety_body(formula)
    if body is not None:
        prefix, loop = _word(lasso, alphabet)
        truth = evaluate(body, lambda g: Periodic(tuple(g.key in s for s in prefix),
                                                  tuple(g.key in s for s in loop)))
        last = next(i for i in range(len(truth.pre) + len(truth.loop)) if not truth.at(i))
        instants = [_instant(lasso, i) for i in range(last + 1)]
        loop_start = None
    else:
        instants = list(lasso.prefix + lasso.loop)
        loop_start = len(lasso.prefix)
    return make_script(model, [i.step for i in instants], [i.chosen for i in instants],
                       loop_start)


def _check_property(model: Model, prop: ast.Property, assumptions: list[F]) -> PropertyOutcome:
    started = time.perf_counter()
    formula = from_ast(prop.formula)
    lasso, alphabet = check_formula(model, formula, assumptions)
    if lasso is None:
        return PropertyOutcome("property", prop.name, True, seconds=time.perf_counter() - started)
    prefix, loop = _word(lasso, alphabet)
    if holds_on_lasso(formula, prefix, loop):  # pragma: no cover - a checker defect
        raise OrccadError(f"internal error: the counterexample to '{prop.name}' does not "
                          "violate it", prop.loc)
    script = _script(model, formula, lasso, alphabet, bool(assumptions))
    kind = "a finite run" if script.loop_start is None else "a run that loops forever"
    return PropertyOutcome("property", prop.name, False, f"{kind} violates it", script,
                   time.perf_counter() - started)


def _check_builtin(model: Model, name: str) -> PropertyOutcome:
    started = time.perf_counter()
    violation = check_builtin(model, name)
    if violation is None:
        return PropertyOutcome("built-in", name, True, seconds=time.perf_counter() - started)
    steps = violation.steps
    script = make_script(model, steps, [()] * len(steps), None)
    return PropertyOutcome("built-in", name, False, violation.message, script,
                   time.perf_counter() - started)


#: The engines of ``orccad check``: the explicit automaton and model, the circuit on BDDs, or
#: the explicit one while it stays small (``auto``, the default).
EXPLICIT, SYMBOLIC, AUTO = "explicit", "symbolic", "auto"
ENGINES = (AUTO, EXPLICIT, SYMBOLIC)
#: ``auto``: the explicit automaton is tabulated while it has at most this many transitions;
#: past them (parallel branches multiply them) the symbolic checker takes over.
AUTO_EXPLICIT_TRANSITIONS = 2_000


def check_mission(program: ast.Program, mission: ast.Mission, *, builtins: bool = True,
                  max_states: int = DEFAULT_MAX_STATES,
                  progress: CheckProgress | None = None, engine: str = AUTO,
                  counters: bool = True) -> MissionReport:
    """Compile ``mission`` in the composed view and check its properties; ``progress`` is told
    the states explored while compiling, then the properties done. ``engine``: see
    :data:`ENGINES`; ``counters``: track counters exactly where the engine can (the explicit
    one), else abstract every data value."""
    if engine not in ENGINES:
        raise OrccadError(f"unknown checker engine '{engine}' (one of {', '.join(ENGINES)})")
    states = None if progress is None else progress.states
    reason = ""
    if engine == AUTO:
        lazy = compose(program, mission, max_states=max_states, lazy=True)
        reason = parallel_tasks(lazy)
        if reason and counters_of(lazy):
            reason = ""  # the explicit model tracks the counters: keep it while it fits
    if engine == EXPLICIT or (engine == AUTO and not reason):
        limit = AUTO_EXPLICIT_TRANSITIONS if engine == AUTO else None
        try:
            composition = compose(program, mission, max_states=max_states, progress=states,
                                  max_transitions=limit)
        except TransitionBudgetExceeded:
            reason = (f"the explicit automaton has more than {AUTO_EXPLICIT_TRANSITIONS} "
                      "transitions")
        else:
            return _check_explicit(program, mission, composition, builtins, progress, counters)
    report = _check_symbolic(program, mission, builtins, progress)
    report.engine_reason = reason
    return report


def _properties_total(program: ast.Program, mission: ast.Mission, builtins: bool) -> int:
    properties = [p for p in applicable(program.properties, mission)
                  if not ast.is_signal_formula(p.formula)]
    return (len(BUILTINS) if builtins else 0) + len(properties)


def _check_explicit(program: ast.Program, mission: ast.Mission, composition: Composition,
                    builtins: bool, progress: CheckProgress | None,
                    counters: bool = True) -> MissionReport:
    model = build_model(composition, counters=counters)
    report = MissionReport(composition, model)
    total = _properties_total(program, mission, builtins)
    if builtins:
        for name in BUILTINS:
            report.outcomes.append(_check_builtin(model, name))
            if progress is not None:
                progress.properties(len(report.outcomes), total)
    assumptions = [from_ast(a.formula) for a in applicable(program.assumptions, mission)]
    for prop in applicable(program.properties, mission):
        if ast.is_signal_formula(prop.formula):
            report.signal_properties.append(prop)
            continue
        report.outcomes.append(_check_property(model, prop, assumptions))
        if progress is not None:
            progress.properties(len(report.outcomes), total)
    return report


def _check_symbolic(program: ast.Program, mission: ast.Mission, builtins: bool,
                    progress: CheckProgress | None) -> MissionReport:
    composition = compose(program, mission, lazy=True)
    model, witness, sizes = symbolic_model(composition)
    try:
        return _symbolic_outcomes(program, mission, builtins, progress, composition, model,
                                  witness, sizes)
    finally:
        release(model, witness)


def _symbolic_outcomes(program, mission, builtins, progress, composition, model, witness,
                       sizes) -> MissionReport:
    report = MissionReport(composition, witness.model, engine=SYMBOLIC, symbolic=sizes)
    total = _properties_total(program, mission, builtins)
    if builtins:
        for name in BUILTINS:
            report.outcomes.append(builtin_outcome(model, witness, name, PropertyOutcome))
            if progress is not None:
                progress.properties(len(report.outcomes), total)
    assumptions = [from_ast(a.formula) for a in applicable(program.assumptions, mission)]
    for prop in applicable(program.properties, mission):
        if ast.is_signal_formula(prop.formula):
            report.signal_properties.append(prop)
            continue
        report.outcomes.append(property_outcome(model, witness, prop, assumptions,
                                                PropertyOutcome, _script))
        if progress is not None:
            progress.properties(len(report.outcomes), total)
    return report


class CheckProgress(Protocol):
    """What :func:`check_mission` reports while it works (a status line on a terminal)."""

    def states(self, explored: int) -> None:
        """``explored`` control states of the composed automaton explored so far."""

    def properties(self, done: int, total: int) -> None:
        """``done`` of ``total`` properties (built-in ones included) decided."""
