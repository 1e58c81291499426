"""From a concrete symbolic run to the explicit model's steps, so that a symbolic
counterexample becomes the same replayable script as an explicit one
(:func:`orccad_app.verify.counterexample.make_script`).

Each instant's registers name a control state of the program (its active pauses and
``pre`` bits): the same state the lazy automaton (:class:`~orccad_app.reactive.lazy.LazyAutomaton`)
numbers. The engine reacts that state with the instant's inputs and data outcomes and gives
the path (inputs it tested, data tests and actions in execution order), the outputs, the
status and the next state: the explicit step the symbolic one stands for. A witness model
(:class:`~orccad_app.verify.model.Model` over the lazy automaton) holds these steps only.
"""

from __future__ import annotations

from orccad_app.reactive import ir
from orccad_app.reactive.automaton import TERMINAL, Action, Leaf
from orccad_app.reactive.status import Status
from orccad_app.reactive.engine import BOOT, react
from orccad_app.reactive.lazy import LazyAutomaton
from orccad_app.reactive.prepare import TERMINATED
from orccad_app.verify.model import ENDED, Model, Path, Step
from orccad_app.reactive.circuit import (BOOT as BOOT_REG, FAILED_BEFORE, TERM,
                                                data_var, input_var, pre_bit, register)
from orccad_app.verify.symbolic.model import SymbolicModel

__all__ = ["Witness"]


class _Oracle:
    """The inputs and data outcomes of one concrete instant, recording the inputs asked."""

    def __init__(self, present: set, outcomes: dict[int, bool]):
        self.present = present
        self.outcomes = outcomes
        self.asked: dict[ir.SignalDecl, bool] = {}

    def input(self, signal: ir.SignalDecl) -> bool:
        answer = self.asked.get(signal)
        if answer is None:
            answer = self.asked[signal] = signal in self.present
        return answer

    def data(self, number: int) -> bool:
        return self.outcomes.get(number, False)


class Witness:
    """Explicit steps of concrete symbolic runs, in a model over the lazy automaton."""

    def __init__(self, symbolic: SymbolicModel):
        self.symbolic = symbolic
        composition = symbolic.composition
        automaton = composition.automaton
        assert isinstance(automaton, LazyAutomaton)
        self.automaton = automaton
        self.prep = automaton.prep
        self.model = Model(composition, ())
        self.model.fairness = list(symbolic.fairness)
        self._index: dict[tuple, int] = {}

    def key(self, point: dict[str, bool]):
        """The control-state key of the registers of ``point``."""
        if point.get(BOOT_REG):
            return BOOT
        if point.get(TERM):
            return TERMINAL
        prep = self.prep
        pauses = [p for p in range(len(prep.pauses)) if point.get(register(p))]
        pres = [prep.pre_base + k for k in range(len(prep.pre_signals))
                if point.get(pre_bit(k))]
        return tuple(pauses + pres)

    def _state(self, key, failed_before: bool) -> int:
        q = self.automaton._state(key)
        entry = (q, (), failed_before)
        number = self._index.get(entry)
        if number is None:
            number = self._index[entry] = len(self.model.states)
            self.model.states.append(entry)
            self.model.steps.append([])
        return number

    def present(self, point: dict[str, bool]) -> set[ir.SignalDecl]:
        return {decl for index, decl in enumerate(self.automaton.inputs)
                if point.get(input_var(index))}

    def step(self, point: dict[str, bool]) -> tuple[Step, tuple[ir.SignalDecl, ...]]:
        """The explicit step of one concrete instant, and the inputs present it does not
        test (the free inputs taken present)."""
        key = self.key(point)
        failed_before = point.get(FAILED_BEFORE, False)
        source = self._state(key, failed_before)
        present = self.present(point)
        if key == TERMINAL:
            step = Step(source, source, None, frozenset(), None, self.model.full_fairness)
            return step, tuple(sorted(present, key=lambda d: d.name))
        outcomes = {n: point.get(data_var(n), False) for n in range(len(self.prep.data_tests))}
        oracle = _Oracle(present, outcomes)
        outcome = react(self.prep, key, oracle)
        program = self.prep.program
        events: list[tuple] = [("in", decl, on) for decl, on in oracle.asked.items()]
        for event in outcome.events:
            if event[0] == "test":
                events.append(("test", event[1], event[2]))
            else:
                events.append(("act", Action(event[0], event[1], event[2], None)))  # type: ignore[arg-type]
        emitted = tuple(s for s in program.outputs if s in outcome.emitted)
        if program.aborted is not None and program.aborted in outcome.emitted:
            status = Status.ABORTED
        elif program.failed is not None and program.failed in outcome.emitted:
            status = Status.FAILED
        else:
            status = Status.DONE if outcome.code == TERMINATED else Status.RUNNING
        target_key = TERMINAL if outcome.code == TERMINATED else outcome.state
        if status == Status.DONE and failed_before:
            shown = ENDED
        else:
            shown = status
        target = self._state(target_key,
                             failed_before or status in (Status.FAILED, Status.ABORTED))
        leaf = Leaf(self.automaton._state(target_key), emitted, status)
        guard = tuple((decl.name, on) for decl, on in oracle.asked.items())
        path = Path(tuple(events), leaf, guard)
        names = frozenset(s.name for s in emitted if not s.name.startswith("_"))
        step = Step(source, target, path, names, shown, 0)
        self.model.steps[source].append(step)
        free = tuple(sorted((d for d in present if d not in oracle.asked), key=lambda d: d.name))
        return step, free
