"""The reference reactor: an :class:`ir.Program` run instant by instant, each instant's
unique coherent execution found by guessing statuses and settling end-of-instant values."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Mapping

from orccad_app.reactive import ir
from tests.reactive.reference.data import Memory
from tests.reactive.reference.errors import Guess, NotCoherent, Pending, ReferenceError_
from tests.reactive.reference.run import Run

__all__ = ["ReferenceReactor", "RefReaction", "MAX_RUNS"]

#: Bound on the executions tried for one instant (guessing is exponential in the worst case).
MAX_RUNS = 4096


@dataclass(frozen=True)
class RefReaction:
    """Same observable fields as :class:`orccad_app.reactive.runtime.Reaction`."""

    outputs: tuple[str, ...]
    values: dict[str, Any]
    status: str
    runs: int = 0  # executions tried to find the coherent one


class ReferenceReactor:
    """Runs an :class:`ir.Program` instant by instant by rewriting its residual term."""

    def __init__(self, program: ir.Program):
        self.program = program
        self.term: Any = program.body
        self.memory = Memory()
        for decl in (*program.inputs, *program.outputs):
            if decl.init is not None:
                self.memory.values[decl] = decl.init
        self.done = False
        self.instant = 0
        self._inputs = {s.name: s for s in program.inputs}

    def react(self, inputs: Mapping[str, Any] | set[str] | frozenset[str] = frozenset(),
              clock_ns: int | None = None) -> RefReaction:
        self.instant += 1
        for relation in self.program.relations:
            if not relation.holds(inputs):
                raise ReferenceError_(f"inputs violate relation {relation.text}")
        self.memory.previous = dict(self.memory.values)
        if clock_ns is not None:
            self.memory.clock_ns = clock_ns
        if isinstance(inputs, Mapping):
            for name, value in inputs.items():
                if value is not None:
                    self.memory.values[self._inputs[name]] = value
        if self.done:
            return RefReaction((), {}, "done")
        final: dict = {}
        tried = 0
        for _ in range(20):  # the end-of-instant values: a fixpoint
            found = self._solve(frozenset(inputs), final)
            tried += found[1]
            if found[0] is not None:
                run = found[0]
                combined = run.combined()
                if combined == final:
                    break
                final = combined
            else:
                learned = {**final, **found[2]}
                if learned == final:
                    raise ReferenceError_("a value is read before it can be known")
                final = learned
        else:
            raise ReferenceError_("end-of-instant values do not settle")
        code, residual = run.react(self.term, {}, ())  # replay the coherent run for its residual
        if code > 1:
            raise ReferenceError_(f"exit escaped the program (code {code})")
        run.memory.values.update(run.combined())
        # a local whose scope did not run (suspended) keeps its status: Esterel v5's pre(S)
        # of a local is its status in the last instant its declaration ran
        kept = {k for k in self.memory.was_present if type(k) is tuple and k not in run.ran}
        run.memory.was_present = frozenset(run.emitted) | frozenset(
            s for s in self.program.inputs if s.name in inputs) | kept
        self.term, self.memory, self.done = residual, run.memory, code == 0
        emitted = [s for s in self.program.outputs if s in run.emitted]
        values = {s.name: run.memory.values.get(s) for s in emitted if s.valued}
        return RefReaction(tuple(s.name for s in emitted), values,
                           "done" if self.done else "running", tried)

    def _solve(self, inputs: frozenset[str], final: dict):
        """The unique coherent execution of this instant, found by guessing statuses: (run or
        None, executions tried, values learned from runs that read a value not known yet)."""
        pending: list[dict] = [{}]
        solutions: list[dict] = []
        learned: dict = {}
        stuck = False
        tried = 0
        while pending:
            assumption = pending.pop()
            tried += 1
            if tried > MAX_RUNS:
                raise ReferenceError_(f"more than {MAX_RUNS} executions in one instant")
            run = Run(self.instant, inputs, assumption, self.memory.copy(), final)
            try:
                run.react(self.term, {}, ())
            except Guess as guess:
                pending.append({**assumption, guess.key: False})
                pending.append({**assumption, guess.key: True})
                continue
            except Pending:
                stuck = True
                for key, (_decl, values) in run.emissions.items():
                    learned.setdefault(key, values[0])
                continue
            if run.coherent():
                solutions.append(assumption)
        if stuck and not solutions:
            return None, tried, learned
        if len(solutions) != 1:
            raise NotCoherent(self.instant, solutions)
        return Run(self.instant, inputs, solutions[0], self.memory.copy(), final), tried, learned
