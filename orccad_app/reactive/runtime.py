"""Running a compiled automaton, one instant at a time.

:class:`Reactor` holds the current state and the data memory and walks the state's reaction
tree for each instant. It is the only code on the hot path of ``orccad react`` and of the
executive: trees are pre-compiled to tuples and closures, so one reaction is a handful of
tuple look-ups.
"""

from __future__ import annotations

from collections.abc import Mapping as _Mapping
from dataclasses import dataclass, field
from typing import Any, Mapping

from orccad_app.diagnostics import OrccadError
from orccad_app.reactive import ir
from orccad_app.reactive.automaton import (ABORTED, FAILED, RUNNING, Action, Automaton,
                                          DataBranch, InputTest, Leaf)
from orccad_app.reactive.expr import Store, Unset, compile_expr, format_expr

__all__ = ["Reaction", "Reactor", "RelationViolation"]


class RelationViolation(OrccadError):
    """The inputs of an instant violate a declared ``relation`` (located at the relation)."""

_LEAF, _INPUT, _DATA, _ACTION = range(4)
_SETS = (frozenset, set)


@dataclass(frozen=True, slots=True)
class Reaction:
    """The result of one instant: outputs emitted (declaration order), their values, status.

    ``status`` is the mission's: once ``failed`` or ``aborted`` it stays so (an ``on fatal``
    block may still be running); ``reason`` names the exception.
    """

    outputs: tuple[str, ...]
    values: dict[str, Any] = field(default_factory=dict)
    status: str = "running"
    state: int = 0
    reason: str | None = None


def _lower(node, data_tests) -> tuple:
    if isinstance(node, Leaf):
        names = tuple(s.name for s in node.emitted)
        valued = tuple(s for s in node.emitted if s.valued)
        return (_LEAF, node.target, names, valued, node.status)
    if isinstance(node, InputTest):
        return (_INPUT, node.signal.name, _lower(node.then, data_tests),
                _lower(node.orelse, data_tests))
    if isinstance(node, DataBranch):
        expr = data_tests[node.number].expr
        return (_DATA, compile_expr(expr), _lower(node.then, data_tests),
                _lower(node.orelse, data_tests), expr)
    assert isinstance(node, Action)
    return (_ACTION, node.kind == "assign", node.target, compile_expr(node.expr),
            _lower(node.next, data_tests), node.expr)


def _pre_read(automaton: Automaton) -> tuple[ir.SignalDecl, ...]:
    """The signals whose ``pre(?S)`` some expression of the automaton reads."""
    found: dict = {}
    stack: list = [*automaton.trees]
    exprs: list = [t.expr for t in automaton.data_tests]
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


class Reactor:
    """An automaton in execution: ``react`` performs one instant."""

    def __init__(self, automaton: Automaton):
        self.automaton = automaton
        self._trees = tuple(_lower(t, automaton.data_tests) for t in automaton.trees)
        self._inputs = {s.name: s for s in automaton.inputs}
        self.state = automaton.initial
        self.store = Store()
        self.status = RUNNING
        self.reason: str | None = None
        self.instant = 0
        program = automaton.program
        self._reasons = {FAILED: program.failed, ABORTED: program.aborted}
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
        store = self.store
        if clock_ns is not None:
            if clock_ns < store.clock_ns:
                raise OrccadError(f"the clock went backwards: {clock_ns} ns after "
                                  f"{store.clock_ns} ns")
            store.clock_ns = clock_ns
        for relation in self._relations:
            if not relation.holds(inputs):
                raise RelationViolation(f"these inputs violate 'relation {relation.text}' "
                                        f"(declared at {relation.loc})", relation.loc)
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
        expr = None
        try:
            while True:
                tag = node[0]
                if tag == _INPUT:
                    node = node[2] if node[1] in inputs else node[3]
                elif tag == _DATA:
                    expr = node[4]
                    node = node[2] if node[1](store) else node[3]
                elif tag == _ACTION:
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
        _, target, names, valued, status = node
        self.state = target
        if status in (FAILED, ABORTED) and self.status not in (FAILED, ABORTED):
            self.status = status
            self.reason = store.values.get(self._reasons[status])
        elif self.status == RUNNING:
            self.status = status
        values = {s.name: store.values.get(s) for s in valued} if valued else {}
        return Reaction(names, values, self.status, target, self.reason)

    @property
    def finished(self) -> bool:
        """The program has terminated (after its ``on fatal`` block, if any)."""
        return self.state == self.automaton.terminal

    @property
    def labels(self) -> frozenset:
        """Labels of the marked regions the current state is in."""
        labels = self.automaton.labels
        return labels[self.state] if labels else frozenset()

    def input_decl(self, name: str) -> ir.SignalDecl | None:
        return self._inputs.get(name)
