"""An independent reference interpreter of the reactive kernel (:mod:`orccad_app.reactive.ir`).

It exists to cross-check the compiler (:mod:`orccad_app.reactive.compiler`, built on the
constructive engine of :mod:`orccad_app.reactive.engine`) and is deliberately written with
other techniques, so that one bug is unlikely to be in both:

*Term rewriting instead of numbered pauses.* The control state is the **residual program**:
the term that is left to execute. Reacting a term gives a completion code and a residual
(Berry's behavioural semantics ``p --(E', k)--> p'``):

================================  =============================================================
``pause``                         pauses (k = 1); residual ``nothing``
``p; q``                          if ``p`` pauses with residual ``p'``: residual ``p'; q``
``loop p``                        ``p`` pauses with ``p'``: residual ``p'; loop p`` (the loop
                                  body restarts as a new term); ``p`` terminating at once is
                                  an instantaneous loop
``p || q``                        ``max`` of the codes; residual: the paused branches' residuals
                                  (branches that terminated become ``nothing``)
``trap T p``                      an exit of T becomes termination; residual ``trap T p'``
``suspend p when t``              first instant: ``p`` reacts; residual is a *started* suspend
                                  (:class:`Suspended`) which, while ``t`` holds, stays as it is
                                  and pauses without doing anything
``signal S p``                    each entry makes a fresh *incarnation* of S; the residual
                                  (:class:`Scoped`) remembers which incarnation its body uses
================================  =============================================================

Completion codes are 0 (terminated), 1 (paused) and, for ``exit T``, a code that grows as the
trap is further out, so that ``max`` in a parallel gives the outermost exit (weak preemption:
every branch still does its whole reaction of the instant).

*Logical coherence instead of Must/Can.* The statuses of output and local signals are not
computed: they are **guessed**. An instant is executed deterministically under an assumption
(a status for each non-input signal it tests); when execution tests a signal the assumption
does not cover, the search splits on it. A complete run is *coherent* when every assumed
status agrees with what the run emitted. Exactly one coherent run is the reaction; none or
several means the program is not logically correct in that instant (:class:`NotCoherent`).
Signals that are never tested need no guess: their status is what is emitted.

*Derived forms interpreted directly.* ``await``, ``abort``, ``every``, ``repeat``, ``race`` …
have node classes here (:class:`Abort`, :class:`Every` …) with rewriting rules of their own,
from their Esterel v5 meaning (a started strong ``abort`` tests its condition before its body
reacts, a weak one after), so the expansions of :mod:`orccad_app.reactive.derived`, which the
compiler receives, are checked too. ``count``/``duration`` are read when the statement starts.

*Values by a fixpoint instead of scheduling.* ``?S`` reads the value S has at the *end* of the
instant (all its emissions of the instant, combined with its ``combine`` operator; two without
one is a run-time error), or its value before the instant when S is not emitted. The instant is
executed under an assumption on those end-of-instant values (none at first) and re-executed
with the values the run emitted until they agree; a read of a value not known yet abandons the
run (the emissions it made are learned). Each local signal incarnation has its own value.
``pre(S)`` and ``pre(?S)`` read the status and value of the previous instant, kept per key
(for a local, of the previous instant its scope ran: suspended instants do not count).
Variables and the clock are evaluated in program order. As in Esterel, where ``abort``/``suspend`` decide their condition once per
instant, a data test *object* (the expansion of ``abort`` shares one between the suspension and
the watcher) is evaluated once per instant, at its first use.
"""

from __future__ import annotations

import operator
from dataclasses import dataclass, field
from typing import Any, Mapping

from orccad_app.reactive import ir

__all__ = ["ReferenceReactor", "RefReaction", "NotCoherent", "ReferenceError_",
           "Suspended", "Scoped", "MAX_RUNS", "Halt", "Sustain", "Await", "AwaitCount",
           "AwaitDuration", "Abort", "AbortCount", "SuspendNow", "LoopEach", "Every", "Repeat", "Race",
           "TrapHandle"]

#: Bound on the executions tried for one instant (guessing is exponential in the worst case).
MAX_RUNS = 4096
_OUTERMOST = 10_000  # exit codes are 2 + _OUTERMOST - (trap nesting depth)

_BINARY = {
    "+": operator.add, "-": operator.sub, "*": operator.mul, "/": operator.truediv,
    "<": operator.lt, "<=": operator.le, ">": operator.gt, ">=": operator.ge,
    "==": operator.eq, "!=": operator.ne, "min": min, "max": max,
    "last": lambda first, second: second,
}


def _componentwise(op):
    """Arithmetic on vectors, component by component (a number with each component)."""
    def apply(left, right):
        vectors = (tuple, list)
        if isinstance(left, vectors) and isinstance(right, vectors):
            if len(left) != len(right):
                raise ValueError("vectors of different sizes")
            return tuple(op(a, b) for a, b in zip(left, right))
        if isinstance(left, vectors):
            return tuple(op(a, right) for a in left)
        if isinstance(right, vectors):
            return tuple(op(left, b) for b in right)
        return op(left, right)
    return apply


for _op in ("+", "-", "*", "/"):
    _BINARY[_op] = _componentwise(_BINARY[_op])


class ReferenceError_(Exception):
    """A run-time error of the program (unset variable, instantaneous loop, bad exit)."""


class NotCoherent(Exception):
    """No or several coherent signal assignments: the instant is not logically correct."""

    def __init__(self, instant: int, solutions: list[dict]):
        self.instant = instant
        self.solutions = solutions
        shown = [{_key_name(k): v for k, v in s.items()} for s in solutions]
        super().__init__(f"instant {instant}: {len(solutions)} coherent assignments {shown}")


def _key_name(key) -> str:
    if isinstance(key, ir.SignalDecl):
        return key.name
    decl, instant, serial = key
    return f"{decl.name}#{instant}.{serial}"


# --------------------------------------------------------------------------- residual terms

@dataclass(frozen=True, slots=True, eq=False)
class Suspended:
    """``suspend body when test`` after its first instant: the test is now checked."""

    test: ir.Test
    body: ir.Stmt


@dataclass(frozen=True, slots=True, eq=False)
class Scoped:
    """The residual of ``signal … { body }``: ``bindings`` maps declarations to incarnations."""

    bindings: tuple[tuple[ir.SignalDecl, tuple], ...]
    body: ir.Stmt


# --------------------------------------------------------------------------- derived forms

def _node(name: str, *fields_: str, doc: str) -> type:
    """A frozen, identity-compared node class with positional ``fields_``."""
    namespace = {"__annotations__": {f: Any for f in fields_}, "__doc__": doc,
                 "__module__": __name__}
    return dataclass(frozen=True, slots=True, eq=False)(type(name, (), namespace))


Halt = _node("Halt", doc="``halt``: pauses forever")
Sustain = _node("Sustain", "signal", doc="``sustain S``: emits S in every instant, forever")
Await = _node("Await", "test", "immediate", doc="``await [immediate] t``")
AwaitCount = _node("AwaitCount", "count", "test", doc="``await n t``: n-th future instant of t")
AwaitDuration = _node("AwaitDuration", "duration", doc="``await d``: first instant past start+d")
Abort = _node("Abort", "body", "test", "weak", "immediate", "handler",
              doc="``[weak] abort body when [immediate] t [do handler]`` (handler may be None)")
AbortCount = _node("AbortCount", "body", "count", "test", "weak", "handler",
                   doc="``[weak] abort body when n t [do handler]``: the n-th later instant of t")
SuspendNow = _node("SuspendNow", "body", "test", doc="``suspend body when immediate t``")
LoopEach = _node("LoopEach", "body", "test", doc="``loop body each t``")
Every = _node("Every", "test", "body", "immediate", doc="``every [immediate] t do body``")
Repeat = _node("Repeat", "count", "body", doc="``repeat n times body``")
Race = _node("Race", "branches", doc="parallel branches; ends when the first one ends")
TrapHandle = _node("TrapHandle", "trap", "body", "handler", doc="``trap T body handle handler``")
# residuals of derived forms after their first instant
_Waiting = _node("_Waiting", "test", doc="``await t`` started: t is now tested")
_Counting = _node("_Counting", "test", "left", doc="``await n t`` with ``left`` occurrences to go")
_Until = _node("_Until", "deadline", doc="``await d`` started: waits for the clock")
_Aborting = _node("_Aborting", "body", "test", "weak", "handler", doc="``abort`` started")
_AbortCounting = _node("_AbortCounting", "body", "left", "test", "weak", "handler",
                       doc="counted ``abort`` started, ``left`` occurrences to go")
_Repeating = _node("_Repeating", "left", "current", "body",
                   doc="``repeat``: ``current`` runs, ``left`` more runs of ``body`` to go")

_NOTHING = ir.Nothing()


class _Pending(Exception):
    """A value read whose end-of-instant value is not known yet (see :class:`ReferenceReactor`)."""


class _Guess(Exception):
    """Execution needs the status of a signal incarnation the assumption does not give."""

    def __init__(self, key):
        self.key = key


# --------------------------------------------------------------------------- one execution

@dataclass
class _Memory:
    """Data: variables, last values of valued signals, the clock."""

    vars: dict = field(default_factory=dict)
    values: dict = field(default_factory=dict)
    clock_ns: int = 0
    previous: dict = field(default_factory=dict)   # pre(?S): values before the instant
    was_present: frozenset = frozenset()            # pre(S): keys present in the last instant

    def copy(self) -> "_Memory":
        return _Memory(dict(self.vars), dict(self.values), self.clock_ns, self.previous,
                       self.was_present)


class _Run:
    """One deterministic execution of an instant under an assumption on signal statuses."""

    def __init__(self, instant: int, inputs: frozenset[str], assumption: dict, memory: _Memory,
                 final_values: dict | None = None):
        self.instant = instant
        self.inputs = inputs
        self.assumption = assumption
        self.memory = memory
        self.emitted: set = set()
        self.tested_data: dict[int, bool] = {}
        self.serial = 0
        self.final_values = final_values or {}  # assumed end-of-instant values, by key
        self.emissions: dict = {}                 # key -> (decl, [values emitted])
        self.scope: dict = {}
        self.ran: set = set()                     # local keys whose scope ran this instant

    # ------------------------------------------------------------------ statements
    def react(self, term, scope: dict, traps: tuple) -> tuple[int, Any]:
        """``(completion code, residual term)`` of ``term`` in this instant."""
        method = _DISPATCH[type(term)]
        return method(self, term, scope, traps)

    def _nothing(self, term, scope, traps):
        return 0, _NOTHING

    def _pause(self, term, scope, traps):
        return 1, _NOTHING

    def _emit(self, term: ir.Emit, scope, traps):
        key = scope.get(term.signal, term.signal)
        self.emitted.add(key)
        if term.value is not None:
            value = self.value(term.value, scope)
            self.emissions.setdefault(key, (term.signal, []))[1].append(value)
        return 0, _NOTHING

    def _assign(self, term: ir.Assign, scope, traps):
        self.memory.vars[term.var] = self.value(term.expr, scope)
        return 0, _NOTHING

    def combined(self) -> dict:
        """The end-of-instant value of each signal key emitted with a value."""
        out = {}
        for key, (decl, values) in self.emissions.items():
            if len(values) > 1 and decl.combine is None:
                raise ReferenceError_(f"{decl.name} emitted twice in one instant")
            value = values[0]
            for other in values[1:]:
                value = _BINARY[decl.combine](value, other) if decl.combine in _BINARY \
                    else (value and other if decl.combine == "and" else value or other)
            out[key] = value
        return out

    def _present(self, term: ir.Present, scope, traps):
        branch = term.then if self.holds(term.test, scope) else term.orelse
        return self.react(branch, scope, traps)

    def _seq(self, term: ir.Seq, scope, traps):
        items = term.items
        for i, item in enumerate(items):
            code, residual = self.react(item, scope, traps)
            if code == 1:
                rest = items[i + 1:]
                return 1, (ir.Seq((residual, *rest)) if rest else residual)
            if code != 0:
                return code, _NOTHING
        return 0, _NOTHING

    def _loop(self, term: ir.Loop, scope, traps):
        code, residual = self.react(term.body, scope, traps)
        if code == 0:
            raise ReferenceError_(f"instantaneous {term.what} at {term.loc}")
        if code == 1:
            return 1, ir.Seq((residual, term))
        return code, _NOTHING

    def _par(self, term: ir.Par, scope, traps):
        results = [self.react(branch, scope, traps) for branch in term.branches]
        code = max(c for c, _ in results)
        if code != 1:
            return code, _NOTHING
        return 1, ir.Par(tuple(r if c == 1 else _NOTHING for c, r in results))

    def _trap(self, term: ir.Trap, scope, traps):
        own = 2 + _OUTERMOST - len(traps)
        code, residual = self.react(term.body, scope, (*traps, term.trap))
        if code == own:
            return 0, _NOTHING
        if code == 1:
            return 1, ir.Trap(term.trap, residual)
        return code, _NOTHING

    def _exit(self, term: ir.Exit, scope, traps):
        for depth in range(len(traps) - 1, -1, -1):
            if traps[depth] is term.trap:
                return 2 + _OUTERMOST - depth, _NOTHING
        raise ReferenceError_(f"exit {term.trap.name} outside its trap")

    def _suspend(self, term: ir.Suspend, scope, traps):
        return self._suspend_body(term.test, term.body, scope, traps)

    def _suspended(self, term: Suspended, scope, traps):
        if self.holds(term.test, scope):
            return 1, term  # frozen: nothing runs, nothing is emitted
        return self._suspend_body(term.test, term.body, scope, traps)

    def _suspend_body(self, test, body, scope, traps):
        code, residual = self.react(body, scope, traps)
        return code, (Suspended(test, residual) if code == 1 else _NOTHING)

    def _local(self, term: ir.Local, scope, traps):
        bindings = []
        for decl in term.signals:
            self.serial += 1
            key = (decl, self.instant, self.serial)
            bindings.append((decl, key))
            if decl.init is not None:
                self.memory.values[key] = decl.init
        return self._scoped(Scoped(tuple(bindings), term.body), scope, traps)

    def _scoped(self, term: Scoped, scope, traps):
        inner = {**scope, **dict(term.bindings)}
        self.ran.update(key for _, key in term.bindings)
        code, residual = self.react(term.body, inner, traps)
        return code, (Scoped(term.bindings, residual) if code == 1 else _NOTHING)

    # ------------------------------------------------------------------ derived forms
    def _halt(self, term, scope, traps):
        return 1, term

    def _sustain(self, term, scope, traps):
        self.emitted.add(scope.get(term.signal, term.signal))
        return 1, term

    def _await(self, term, scope, traps):
        if term.immediate and self.holds(term.test, scope):
            return 0, _NOTHING
        return 1, _Waiting(term.test)

    def _waiting(self, term, scope, traps):
        return (0, _NOTHING) if self.holds(term.test, scope) else (1, term)

    def _await_count(self, term, scope, traps):
        return 1, _Counting(term.test, self.value(term.count, scope))

    def _counting(self, term, scope, traps):
        if not self.holds(term.test, scope):
            return 1, term
        return (0, _NOTHING) if term.left <= 1 else (1, _Counting(term.test, term.left - 1))

    def _await_duration(self, term, scope, traps):
        return 1, _Until(self.memory.clock_ns + self.value(term.duration, scope))

    def _until(self, term, scope, traps):
        return (0, _NOTHING) if self.memory.clock_ns >= term.deadline else (1, term)

    def _abort(self, term, scope, traps):
        strong_now = term.immediate and not term.weak
        if strong_now and self.holds(term.test, scope):
            return self._aborted(term.handler, scope, traps)
        return self._abort_body(term.body, term, term.weak and term.immediate, scope, traps)

    def _aborting(self, term, scope, traps):
        if not term.weak and self.holds(term.test, scope):
            return self._aborted(term.handler, scope, traps)
        return self._abort_body(term.body, term, term.weak, scope, traps)

    def _abort_body(self, body, term, test_after: bool, scope, traps):
        """The body reacts; a weak abort then tests its condition (the body had its say)."""
        code, residual = self.react(body, scope, traps)
        if code != 1:
            return code, _NOTHING
        if test_after and self.holds(term.test, scope):
            return self._aborted(term.handler, scope, traps)
        return 1, _Aborting(residual, term.test, term.weak, term.handler)

    def _aborted(self, handler, scope, traps):
        return (0, _NOTHING) if handler is None else self.react(handler, scope, traps)

    def _abort_count(self, term, scope, traps):
        left = self.value(term.count, scope)
        return self._count_body(term.body, term, left, False, scope, traps)

    def _abort_counting(self, term, scope, traps):
        left, fired = term.left, False
        if self.holds(term.test, scope):
            left -= 1
            fired = left <= 0
        if fired and not term.weak:
            return self._aborted(term.handler, scope, traps)
        return self._count_body(term.body, term, left, fired, scope, traps)

    def _count_body(self, body, term, left, fired, scope, traps):
        """The body reacts; a weak counted abort whose count is reached then dies."""
        code, residual = self.react(body, scope, traps)
        if code != 1:
            return code, _NOTHING
        if fired:
            return self._aborted(term.handler, scope, traps)
        return 1, _AbortCounting(residual, left, term.test, term.weak, term.handler)

    def _mark(self, term, scope, traps):
        return self.react(term.body, scope, traps)

    def _suspend_now(self, term, scope, traps):
        if self.holds(term.test, scope):
            return 1, term  # not started yet
        return self._suspend_body(term.test, term.body, scope, traps)

    def _loop_each(self, term, scope, traps):
        body = Abort(ir.Seq((term.body, Halt())), term.test, False, False, None)
        return self.react(ir.Loop(body, what="loop … each"), scope, traps)

    def _every(self, term, scope, traps):
        start = Await(term.test, term.immediate)
        return self.react(ir.Seq((start, LoopEach(term.body, term.test))), scope, traps)

    def _repeat(self, term, scope, traps):
        return self._repeat_from(self.value(term.count, scope), term.body, scope, traps)

    def _repeating(self, term, scope, traps):
        code, residual = self.react(term.current, scope, traps)
        if code == 0:
            return self._repeat_from(term.left, term.body, scope, traps)
        return code, (_Repeating(term.left, residual, term.body) if code == 1 else _NOTHING)

    def _repeat_from(self, left, body, scope, traps):
        if left <= 0:
            return 0, _NOTHING
        code, residual = self.react(body, scope, traps)
        if code == 0:
            raise ReferenceError_("instantaneous repeat body")
        return code, (_Repeating(left - 1, residual, body) if code == 1 else _NOTHING)

    def _race(self, term, scope, traps):
        results = [self.react(branch, scope, traps) for branch in term.branches]
        code = max(c for c, _ in results)
        if code >= 2:
            return code, _NOTHING
        if any(c == 0 for c, _ in results):
            return 0, _NOTHING
        return 1, Race(tuple(r for _, r in results))

    def _trap_handle(self, term, scope, traps):
        own = 2 + _OUTERMOST - len(traps)
        code, residual = self.react(term.body, scope, (*traps, term.trap))
        if code == own:
            return self._aborted(term.handler, scope, traps)
        if code == 1:
            return 1, TrapHandle(term.trap, residual, term.handler)
        return code, _NOTHING

    # ------------------------------------------------------------------ tests and data
    def holds(self, test: ir.Test, scope: dict) -> bool:
        kind = type(test)
        if kind is ir.SigRef:
            decl = test.signal
            if decl.kind == ir.INPUT:
                return decl.name in self.inputs
            key = scope.get(decl, decl)
            if key not in self.assumption:
                raise _Guess(key)
            return self.assumption[key]
        if kind is ir.PreRef:
            return scope.get(test.signal, test.signal) in self.memory.was_present
        if kind is ir.SigNot:
            return not self.holds(test.operand, scope)
        if kind is ir.SigAnd:
            return self.holds(test.left, scope) and self.holds(test.right, scope)
        if kind is ir.SigOr:
            return self.holds(test.left, scope) or self.holds(test.right, scope)
        assert kind is ir.DataTest
        if id(test) not in self.tested_data:
            self.tested_data[id(test)] = bool(self.value(test.expr, scope))
        return self.tested_data[id(test)]

    def value(self, expr: ir.Expr, scope: dict) -> Any:
        kind = type(expr)
        if kind is ir.Const:
            return expr.value
        if kind is ir.VarRef:
            if expr.var not in self.memory.vars:
                raise ReferenceError_(f"variable {expr.var.name} read before assigned")
            return self.memory.vars[expr.var]
        if kind is ir.SigValue:
            key = scope.get(expr.signal, expr.signal)
            if key in self.final_values:
                return self.final_values[key]
            if key not in self.memory.values:
                raise _Pending(key)
            return self.memory.values[key]
        if kind is ir.PreValue:
            key = scope.get(expr.signal, expr.signal)
            if key not in self.memory.previous:
                if type(key) is tuple and expr.signal.init is not None:
                    return expr.signal.init  # a fresh incarnation: its initial value
                raise ReferenceError_(f"pre(?{expr.signal.name}) read before any value")
            return self.memory.previous[key]
        if kind is ir.Clock:
            return self.memory.clock_ns
        if kind is ir.VectorExpr:
            return tuple(self.value(item, scope) for item in expr.items)
        if kind is ir.Unary:
            operand = self.value(expr.operand, scope)
            if expr.op == "-":
                return tuple(-v for v in operand) if isinstance(operand, tuple) else -operand
            return not operand
        if expr.op == "and":
            return bool(self.value(expr.left, scope)) and bool(self.value(expr.right, scope))
        if expr.op == "or":
            return bool(self.value(expr.left, scope)) or bool(self.value(expr.right, scope))
        return _BINARY[expr.op](self.value(expr.left, scope), self.value(expr.right, scope))

    def coherent(self) -> bool:
        return all((key in self.emitted) == status for key, status in self.assumption.items())


_DISPATCH = {
    ir.Nothing: _Run._nothing, ir.Pause: _Run._pause, ir.Emit: _Run._emit,
    ir.Assign: _Run._assign, ir.Present: _Run._present, ir.Seq: _Run._seq,
    ir.Loop: _Run._loop, ir.Par: _Run._par, ir.Trap: _Run._trap, ir.Exit: _Run._exit,
    ir.Suspend: _Run._suspend, Suspended: _Run._suspended, ir.Local: _Run._local,
    Scoped: _Run._scoped, Halt: _Run._halt, Sustain: _Run._sustain, Await: _Run._await,
    _Waiting: _Run._waiting, AwaitCount: _Run._await_count, _Counting: _Run._counting,
    AwaitDuration: _Run._await_duration, _Until: _Run._until, Abort: _Run._abort,
    _Aborting: _Run._aborting, SuspendNow: _Run._suspend_now, LoopEach: _Run._loop_each,
    Every: _Run._every, Repeat: _Run._repeat, _Repeating: _Run._repeating, Race: _Run._race,
    TrapHandle: _Run._trap_handle, AbortCount: _Run._abort_count,
    _AbortCounting: _Run._abort_counting, ir.Mark: _Run._mark,
}


# --------------------------------------------------------------------------- the reactor

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
        self.memory = _Memory()
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
            run = _Run(self.instant, inputs, assumption, self.memory.copy(), final)
            try:
                run.react(self.term, {}, ())
            except _Guess as guess:
                pending.append({**assumption, guess.key: False})
                pending.append({**assumption, guess.key: True})
                continue
            except _Pending:
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
        return _Run(self.instant, inputs, solutions[0], self.memory.copy(), final), tried, learned
