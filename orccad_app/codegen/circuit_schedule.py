"""The run-time order of a circuit's data actions and tests, made static (or refused).

The explicit engine performs an instant's data events (assignments, valued emissions, data
tests) in the order :func:`orccad_app.reactive.engine._schedule` sorts them: by the walk in
which each became sure and ready (:meth:`orccad_app.reactive.walk.Walk.record`), then by its
position in the walk. The circuit's C runs them in one fixed order, the walk's
(:attr:`Circuit.activations`), each where its sure activation holds. :func:`schedule` keeps
that order where it gives the engine's results and refuses the program otherwise
(:class:`NotStatic`, the generator then writes the explicit automaton):

- an event reading ``?S`` placed before an emission of S that may run in the same instant
  (the engine makes the read wait for every emission);
- two events that touch the same data (one writes a variable or a signal value the other
  reads or writes) and may run in one instant in the other order: the later one in the walk
  may become sure in an earlier walk of the fixpoint (its path does not wait for a signal
  status the earlier one's does) or wait for fewer values;
- the old incarnation of a local signal read after its new one was given a value (the engine
  refuses it at compile time);
- an event whose activation depends on a data test not evaluated before it.

Run-time errors of two independent events of one instant are reported in the walk's order;
the engine may report the other one first (only which error is named differs, the instant
fails in both).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import cast

from orccad_app.diagnostics import SourceLocation
from orccad_app.reactive import ir
from orccad_app.reactive.bdd import Node
from orccad_app.reactive.circuit import Activation, Circuit, data_var

__all__ = ["Event", "NotStatic", "schedule", "variables_read"]


class NotStatic(Exception):
    """The circuit's events have no static order: ``reason`` says why, ``loc`` where."""

    def __init__(self, reason: str, loc: SourceLocation | None):
        super().__init__(reason)
        self.reason = reason
        self.loc = loc


@dataclass(frozen=True)
class Event:
    """One scheduled event: ``activation.sure`` is where it runs (a function of the
    registers, the inputs and the data tests before it)."""

    activation: Activation


def variables_read(expr: ir.Expr | None) -> set:
    """The variables ``expr`` reads."""
    found: set = set()
    stack = [] if expr is None else [expr]
    while stack:
        node = stack.pop()
        if isinstance(node, ir.VarRef):
            found.add(node.var)
        elif isinstance(node, ir.Unary):
            stack.append(node.operand)
        elif isinstance(node, ir.Binary):
            stack.extend((node.left, node.right))
        elif isinstance(node, ir.VectorExpr):
            stack.extend(node.items)
    return found


def _writes(a: Activation) -> set:
    if a.kind == "assign":
        return {("var", a.target)}
    if a.kind in ("emit", "init"):
        return {("sig", a.key)}
    return set()


def _reads(a: Activation) -> set:
    return ({("var", v) for v in variables_read(a.expr)}
            | {("sig", key) for key in a.reads})


def _loc(a: Activation) -> SourceLocation | None:
    loc = getattr(a.expr, "loc", None)
    return loc if loc is not None else getattr(a.node.src, "loc", None)


def schedule(circuit: Circuit, care: Node) -> list[Event]:
    """The events of ``circuit`` in a static order where the registers lie in ``care`` (the
    reachable states: :mod:`.circuit_reach`), or :class:`NotStatic` (raised from a frame
    holding no BDD node: a traceback kept alive must not keep CUDD nodes past their
    manager)."""
    try:
        return _schedule(circuit, care)
    except NotStatic as error:
        problem = NotStatic(error.reason, error.loc)
    del care
    raise problem


def _schedule(circuit: Circuit, care: Node) -> list[Event]:
    m = circuit.manager
    for where, loc, name in circuit.undecided:
        if where & care == m.false:
            continue
        raise NotStatic(f"the status of {name} may be undecided (non-constructive in some "
                        "state)", loc)
    events = [a for a in circuit.activations if a.sure != m.false]
    writes = [_writes(a) for a in events]
    reads = [_reads(a) for a in events]
    levels = _value_levels(circuit, events, writes, reads)
    rounds = circuit.activation_rounds
    for j, later in enumerate(events):
        for i in range(j):
            earlier = events[i]
            both = earlier.sure & later.sure & care
            if both == m.false:
                continue
            if writes[j] & reads[i] and any(k[0] == "sig" for k in writes[j] & reads[i]):
                raise NotStatic("a value is read before, in the walk, an emission of its "
                                "signal in the same instant", _loc(earlier))
            if _old_after_new(writes[i], reads[j]):
                raise NotStatic("the old incarnation of a local signal is read after its "
                                "new one was given a value", _loc(later))
            touch = (writes[j] & (writes[i] | reads[i])) or (writes[i] & reads[j])
            if not touch:
                continue
            if levels[i] > levels[j]:
                raise NotStatic("an event waits for more values than a later one touching "
                                "the same data", _loc(earlier))
            # (cast: with Node = Any, mypy takes dict.get's default-None overload)
            inverted = m.any(r.get(later.visit, m.false)
                             & ~cast(Node, r.get(earlier.visit, m.false)) for r in rounds)
            if inverted & both != m.false:
                raise NotStatic("an event becomes sure after a later one touching the same "
                                "data (its path waits for a signal's status)", _loc(earlier))
    _check_tests_before(circuit, events, care)
    return [Event(a) for a in events]


def _old_after_new(written: set, read: set) -> bool:
    for kind, key in written:
        if kind == "sig" and type(key) is tuple and not key[1]:
            if ("sig", (key[0], True)) in read:
                return True
    return False


def _value_levels(circuit: Circuit, events: list[Activation], writes: list[set],
                  reads: list[set]) -> list[int]:
    """How many walks of values each event waits at least (the engine's ``not_ready``):
    one more than the emissions of a signal whose value it reads (every valued signal waits
    one walk), as much as the assignments of the variables it reads."""
    valued = circuit.prep.valued_emitted
    levels = [0] * len(events)
    for _ in range(len(events) + 1):
        changed = False
        for j in range(len(events)):
            level = 0
            for kind, key in reads[j]:
                if kind == "sig":
                    decl = key[0] if type(key) is tuple else key
                    if decl in valued:
                        level = max(level, 1 + max((levels[i] for i in range(len(events))
                                                    if ("sig", key) in writes[i]), default=0))
                else:
                    level = max(level, max((levels[i] for i in range(len(events))
                                            if ("var", key) in writes[i]), default=0))
            if level != levels[j]:
                levels[j] = level
                changed = True
        if not changed:
            return levels
    raise NotStatic("the values of the instant depend on each other in a cycle",
                    _loc(events[0]) if events else None)


def _check_tests_before(circuit: Circuit, events: list[Activation], care: Node) -> None:
    """Every event's activation reads only data tests already decided where it holds."""
    m = circuit.manager
    decided: dict[int, Node] = {}
    for a in events:
        _independent(m, a.sure & care, decided, a)
        if a.kind == "test":
            number = cast(int, a.target)  # a test's target: its data test's number
            decided[number] = decided.get(number, m.false) | a.sure
    finals = [*circuit.next.values(), *circuit.emitted.values(), circuit.code0]
    for f in finals:
        _independent(m, f & care, decided, None)


def _independent(m, f: Node, decided: dict[int, Node], a: Activation | None) -> None:
    for name in m.support(f):
        if not name.startswith("d"):
            continue
        number = int(name[1:])
        rest = f & ~decided.get(number, m.false)
        if rest == m.false:
            continue
        one = m.bdd.let({data_var(number): m.true}, rest)
        zero = m.bdd.let({data_var(number): m.false}, rest)
        if one != zero:
            raise NotStatic(f"a data test (number {number}) decides an event before it is "
                            "evaluated", _loc(a) if a is not None else None)
