"""Running a compiled automaton, one instant at a time.

:class:`Reactor` holds the current state and the data memory and walks the state's reaction
tree for each instant. It is the only code on the hot path of ``orccad react`` and of the
executive: trees are pre-compiled to tuples and closures (:mod:`.lowered`), so one reaction is a
handful of tuple look-ups. :meth:`Reactor.step` is the lean path (it returns the leaf's
precomputed :class:`~orccad_app.reactive.lowered.Step`); :meth:`Reactor.react` builds a
:class:`Reaction` record on top of it. A :class:`~orccad_app.reactive.lazy.LazyAutomaton` runs
the same way, its trees growing as instants need them.
"""

from __future__ import annotations

from collections.abc import Mapping as _Mapping
from dataclasses import dataclass, field
from typing import Any, Mapping

from orccad_app.diagnostics import OrccadError
from orccad_app.reactive import ir
from orccad_app.reactive.automaton import Action, Automaton, DataBranch, InputTest
from orccad_app.reactive.status import Status
from orccad_app.reactive.expr import Store, Unset, format_expr
from orccad_app.reactive.lazy import LazyAutomaton
from orccad_app.reactive.lowered import ACTION, DATA, INPUT, Step, lower

__all__ = ["AutomatonPosition", "Reaction", "Reactor", "RelationViolation", "Step"]


class RelationViolation(OrccadError):
    """The inputs of an instant violate a declared ``relation`` (located at the relation)."""

_SETS = (frozenset, set)
_FAILING = (Status.FAILED, Status.ABORTED)


@dataclass(frozen=True, slots=True)
class Reaction:
    """The result of one instant: outputs emitted (declaration order), their values, status.

    ``status`` is the mission's: once ``failed`` or ``aborted`` it stays so (an ``on fatal``
    block may still be running); ``reason`` names the exception.
    """

    outputs: tuple[str, ...]
    values: dict[str, Any] = field(default_factory=dict)
    status: Status = Status.RUNNING
    state: int = 0
    reason: str | None = None


def _pre_read(automaton: Automaton | LazyAutomaton) -> tuple[ir.SignalDecl, ...]:
    """The signals whose ``pre(?S)`` some expression of the automaton reads."""
    found: dict = {}
    exprs: list = [t.expr for t in automaton.data_tests]
    if isinstance(automaton, LazyAutomaton):
        exprs.extend(automaton.expressions())
    else:
        stack: list = [*automaton.trees]
        while stack:
            node = stack.pop()
            if isinstance(node, Action):
                exprs.append(node.expr)
                stack.append(node.next)
            elif isinstance(node, (InputTest, DataBranch)):
                stack.extend((node.then, node.orelse))
    while exprs:
        expr = exprs.pop()
        if isinstance(expr, ir.PreValue):
            found[expr.signal] = None
        elif isinstance(expr, ir.Unary):
            exprs.append(expr.operand)
        elif isinstance(expr, ir.Binary):
            exprs.extend((expr.left, expr.right))
        elif isinstance(expr, ir.VectorExpr):
            exprs.extend(expr.items)
    return tuple(found)


class AutomatonPosition:
    """Where a runtime of ``automaton`` is (``state``): what a state's number says of the
    program, for every runtime that steps a compiled automaton (this module's
    :class:`Reactor`, a controller's C automaton)."""

    automaton: Automaton | LazyAutomaton
    state: int

    @property
    def finished(self) -> bool:
        """The program has terminated (after its ``on fatal`` block, if any)."""
        return self.state == self.automaton.terminal

    @property
    def labels(self) -> frozenset:
        """Labels of the marked regions the current state is in."""
        labels = self.automaton.labels
        return labels[self.state] if labels else frozenset()


class Reactor(AutomatonPosition):
    """An automaton in execution: ``react`` (or the lean ``step``) performs one instant."""

    def __init__(self, automaton: Automaton | LazyAutomaton):
        self.automaton = automaton
        if isinstance(automaton, LazyAutomaton):
            self._lazy: LazyAutomaton | None = automaton
            self._trees: list | tuple = automaton.roots  # grows with the automaton
        else:
            self._lazy = None
            self._trees = tuple(lower(t, automaton.data_tests) for t in automaton.trees)
        self._inputs = {s.name: s for s in automaton.inputs}
        self.state = automaton.initial
        self.store = Store()
        self.status: Status = Status.RUNNING
        self.reason: str | None = None
        self.instant = 0
        program = automaton.program
        self._reasons = {Status.FAILED: program.failed, Status.ABORTED: program.aborted}
        for decl in (*program.inputs, *program.outputs):
            if decl.init is not None:
                self.store.values[decl] = decl.init
        self._previous = _pre_read(automaton)
        self._relations = program.relations

    def react(self, inputs: Mapping[str, Any] | frozenset[str] | set[str] = frozenset(),
              clock_ns: int | None = None) -> Reaction:
        """One instant with ``inputs`` present (a mapping gives valued inputs their values).

        ``clock_ns`` sets this instant's executive clock; it may not go backwards.
        """
        step = self.step(inputs, clock_ns)
        valued = step.valued
        values = {s.name: self.store.values.get(s) for s in valued} if valued else {}
        return Reaction(step.outputs, values, self.status, step.target, self.reason)

    def step(self, inputs: Mapping[str, Any] | frozenset[str] | set[str] = frozenset(),
             clock_ns: int | None = None) -> Step:
        """One instant, as :meth:`react`, returning the reached leaf's precomputed
        :class:`Step` (no allocation): the mission's status is :attr:`status`, the values of
        the valued outputs :meth:`values`."""
        store = self.store
        if clock_ns is not None:
            if clock_ns < store.clock_ns:
                raise OrccadError(f"the clock went backwards: {clock_ns} ns after "
                                  f"{store.clock_ns} ns")
            store.clock_ns = clock_ns
        if self._relations:
            self._check_relations(inputs)
        if self._previous:
            values = store.values
            store.previous = {d: values.get(d, ir.NO_VALUE) for d in self._previous}
        # plain sets skip the ABC check (isinstance on typing.Mapping costs ~0.4 µs, a third
        # of a reaction)
        if type(inputs) not in _SETS and isinstance(inputs, _Mapping):
            for name, value in inputs.items():
                if value is not None:
                    store.values[self._inputs[name]] = value
        self.instant += 1
        node = self._trees[self.state]
        if node is None:
            node = self._grow(inputs)
        expr = None
        try:
            while True:
                tag = node[0]
                if tag == INPUT:
                    node = node[2] if node[1] in inputs else node[3]
                    if node is None:  # a lazy tree: this path is not built yet
                        node = self._grow(inputs)
                elif tag == DATA:
                    expr = node[4]
                    node = node[2] if node[1](store) else node[3]
                elif tag == ACTION:
                    expr = node[5]
                    if node[1]:
                        store.vars[node[2]] = node[3](store)
                    else:
                        store.values[node[2]] = node[3](store)
                    node = node[4]
                else:
                    break
        except (Unset, TypeError, ValueError, ZeroDivisionError, ArithmeticError) as error:
            where = "" if isinstance(expr, ir.Fault) else f" in {format_expr(expr)}"
            raise OrccadError(f"run-time error{where}: {error}",
                              getattr(expr, "loc", None)) from None
        step: Step = node[1]
        self.state = step.target
        if step.status != Status.RUNNING:
            self._settle(step.status)
        return step

    def _grow(self, inputs) -> tuple | list:
        """The current state's tree after building the path ``inputs`` take (lazy automata):
        input tests come before any data action, so the walk restarts from the root."""
        assert self._lazy is not None
        return self._lazy.expand(self.state, inputs)

    def _check_relations(self, inputs) -> None:
        for relation in self._relations:
            if not relation.holds(inputs):
                raise RelationViolation(f"these inputs violate 'relation {relation.text}' "
                                        f"(declared at {relation.loc})", relation.loc)

    def _settle(self, status: Status) -> None:
        """The mission's status after an instant of status ``status`` (not ``running``)."""
        if status in _FAILING and self.status not in _FAILING:
            self.status = status
            self.reason = self.store.values.get(self._reasons[status])
        elif self.status == Status.RUNNING:
            self.status = status

    def values(self, step: Step) -> dict[str, Any]:
        """The values of ``step``'s valued outputs (just after that step)."""
        values = self.store.values
        return {s.name: values.get(s) for s in step.valued}

    def input_decl(self, name: str) -> ir.SignalDecl | None:
        return self._inputs.get(name)
