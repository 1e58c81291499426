"""One deterministic execution of an instant under an assumption on signal statuses."""

from __future__ import annotations

from typing import Any

from orccad_app.reactive import ir
from tests.reactive.reference.data import BINARY, Memory
from tests.reactive.reference.derived_forms import DerivedForms
from tests.reactive.reference.errors import Guess, Pending, ReferenceError_
from tests.reactive.reference.terms import (
    NOTHING, OUTERMOST, Abort, AbortCount, AbortCounting, Aborting, Await, AwaitCount,
    AwaitDuration, Counting, Every, Halt, LoopEach, Race, Repeat, Repeating, Scoped, Suspended,
    SuspendNow, Sustain, TrapHandle, Until, Waiting,
)

__all__ = ["Run"]


class Run(DerivedForms):
    """One deterministic execution of an instant under an assumption on signal statuses."""

    def __init__(self, instant: int, inputs: frozenset[str], assumption: dict, memory: Memory,
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
        return 0, NOTHING

    def _pause(self, term, scope, traps):
        return 1, NOTHING

    def _emit(self, term: ir.Emit, scope, traps):
        key = scope.get(term.signal, term.signal)
        self.emitted.add(key)
        if term.value is not None:
            value = self.value(term.value, scope)
            self.emissions.setdefault(key, (term.signal, []))[1].append(value)
        return 0, NOTHING

    def _assign(self, term: ir.Assign, scope, traps):
        self.memory.vars[term.var] = self.value(term.expr, scope)
        return 0, NOTHING

    def combined(self) -> dict:
        """The end-of-instant value of each signal key emitted with a value."""
        out = {}
        for key, (decl, values) in self.emissions.items():
            if len(values) > 1 and decl.combine is None:
                raise ReferenceError_(f"{decl.name} emitted twice in one instant")
            value = values[0]
            for other in values[1:]:
                value = BINARY[decl.combine](value, other) if decl.combine in BINARY \
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
                return code, NOTHING
        return 0, NOTHING

    def _loop(self, term: ir.Loop, scope, traps):
        code, residual = self.react(term.body, scope, traps)
        if code == 0:
            raise ReferenceError_(f"instantaneous {term.what} at {term.loc}")
        if code == 1:
            return 1, ir.Seq((residual, term))
        return code, NOTHING

    def _par(self, term: ir.Par, scope, traps):
        results = [self.react(branch, scope, traps) for branch in term.branches]
        code = max(c for c, _ in results)
        if code != 1:
            return code, NOTHING
        return 1, ir.Par(tuple(r if c == 1 else NOTHING for c, r in results))

    def _trap(self, term: ir.Trap, scope, traps):
        own = 2 + OUTERMOST - len(traps)
        code, residual = self.react(term.body, scope, (*traps, term.trap))
        if code == own:
            return 0, NOTHING
        if code == 1:
            return 1, ir.Trap(term.trap, residual)
        return code, NOTHING

    def _exit(self, term: ir.Exit, scope, traps):
        for depth in range(len(traps) - 1, -1, -1):
            if traps[depth] is term.trap:
                return 2 + OUTERMOST - depth, NOTHING
        raise ReferenceError_(f"exit {term.trap.name} outside its trap")

    def _suspend(self, term: ir.Suspend, scope, traps):
        return self._suspend_body(term.test, term.body, scope, traps)

    def _suspended(self, term: Suspended, scope, traps):
        if self.holds(term.test, scope):
            return 1, term  # frozen: nothing runs, nothing is emitted
        return self._suspend_body(term.test, term.body, scope, traps)

    def _suspend_body(self, test, body, scope, traps):
        code, residual = self.react(body, scope, traps)
        return code, (Suspended(test, residual) if code == 1 else NOTHING)

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
        return code, (Scoped(term.bindings, residual) if code == 1 else NOTHING)

    # ------------------------------------------------------------------ tests and data
    def holds(self, test: ir.Test, scope: dict) -> bool:
        kind = type(test)
        if kind is ir.SigRef:
            decl = test.signal
            if decl.kind == ir.INPUT:
                return decl.name in self.inputs
            key = scope.get(decl, decl)
            if key not in self.assumption:
                raise Guess(key)
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
                raise Pending(key)
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
        return BINARY[expr.op](self.value(expr.left, scope), self.value(expr.right, scope))

    def coherent(self) -> bool:
        return all((key in self.emitted) == status for key, status in self.assumption.items())


_DISPATCH = {
    ir.Nothing: Run._nothing, ir.Pause: Run._pause, ir.Emit: Run._emit,
    ir.Assign: Run._assign, ir.Present: Run._present, ir.Seq: Run._seq,
    ir.Loop: Run._loop, ir.Par: Run._par, ir.Trap: Run._trap, ir.Exit: Run._exit,
    ir.Suspend: Run._suspend, Suspended: Run._suspended, ir.Local: Run._local,
    Scoped: Run._scoped, Halt: Run._halt, Sustain: Run._sustain, Await: Run._await,
    Waiting: Run._waiting, AwaitCount: Run._await_count, Counting: Run._counting,
    AwaitDuration: Run._await_duration, Until: Run._until, Abort: Run._abort,
    Aborting: Run._aborting, SuspendNow: Run._suspend_now, LoopEach: Run._loop_each,
    Every: Run._every, Repeat: Run._repeat, Repeating: Run._repeating, Race: Run._race,
    TrapHandle: Run._trap_handle, AbortCount: Run._abort_count,
    AbortCounting: Run._abort_counting, ir.Mark: Run._mark,
}
