"""One reaction of a prepared program, by Esterel's constructive semantics.

The control state is the set of active pauses. A reaction walks the program in *surface*
mode (statements started in this instant) or *depth* mode (statements resumed from an active
pause), computing completion codes (0 terminated, 1 paused, ≥ 2 trap exits; ``max`` wins in
parallel) exactly as Berry's structural semantics do.

Signal statuses are found constructively. One walk computes, for the current knowledge of
signal statuses, what *must* be emitted (on paths that are sure to run) and what *can* be
emitted (on every path that may run). Signals tested while unknown are then set present if they
must be emitted and absent if they cannot be; the walk is repeated until every tested signal is
known. If a walk makes no progress, the program is not constructive for that state and inputs:
a compile error names the signal and the test that depends on it.

Inputs and data tests are decided by an *oracle*, which is how :mod:`.compiler` explores all
cases symbolically: it asks for an input's presence or a data test's outcome when the walk
needs it, never earlier. The last walk (no unknowns left) records, in order, the data actions
to perform at run time (assignments, valued emissions, data tests) and the next control state.
"""

from __future__ import annotations

from bisect import bisect_left, bisect_right
from dataclasses import dataclass
from typing import Any, Protocol

from orccad_app.diagnostics import OrccadError
from orccad_app.reactive import ir
from orccad_app.reactive.prepare import (
    ASSIGN, EMIT, EXIT, LOCAL, LOOP, MARK, NOTHING, PAR, PAUSE, PRESENT, SEQ, SUSPEND, TRAP,
    KNode, Prepared,
)

__all__ = ["Oracle", "Outcome", "react", "BOOT"]

#: The control state before the first instant (nothing started yet).
BOOT: tuple[int, ...] | None = None


class Oracle(Protocol):
    """Decides what the program's inputs and data are, when the engine asks."""

    def input(self, signal: ir.SignalDecl) -> bool: ...
    def data(self, number: int) -> bool: ...


@dataclass(frozen=True, slots=True)
class Outcome:
    """What one reaction does.

    ``events`` are the run-time actions in execution order: ``("assign", VarDecl, Expr)``,
    ``("emit", SignalDecl, Expr)`` for a valued emission, ``("test", number, bool)`` for a
    data test and its outcome. ``emitted`` holds the output signals emitted, ``code`` the
    completion code of the program and ``state`` the next control state (sorted pauses).
    """

    events: tuple[tuple[Any, ...], ...]
    emitted: frozenset[ir.SignalDecl]
    code: int
    state: tuple[int, ...]


class _Walk:
    """Mutable scratch of one walk over the program."""

    __slots__ = ("prep", "active", "oracle", "env", "must", "can", "unknown", "unknown_at",
                 "events", "next", "tested")

    def __init__(self, prep: Prepared, active: tuple[int, ...], oracle: Oracle, env: dict):
        self.prep = prep
        self.active = active
        self.oracle = oracle
        self.env = env
        self.must: set = set()
        self.can: set = set()
        self.unknown: dict = {}
        self.unknown_at: dict = {}
        self.events: list = []
        self.next: list[int] = []
        self.tested: set[int] = set()

    # ------------------------------------------------------------------ helpers
    def selected(self, node: KNode) -> bool:
        active = self.active
        i = bisect_left(active, node.lo)
        return i < len(active) and active[i] < node.hi

    def test(self, test: ir.Test, scope: dict, sure: bool) -> bool | None:
        kind = type(test)
        if kind is ir.SigRef:
            decl = test.signal
            if decl.kind == ir.INPUT:
                return self.oracle.input(decl)
            key = scope.get(decl, decl)
            status = self.env.get(key)
            if status is None:
                self.unknown[key] = decl
                self.unknown_at.setdefault(key, test.loc)
            return status
        if kind is ir.DataTest:
            number = self.prep.data_test_index[id(test)]
            outcome = self.oracle.data(number)
            if sure and number not in self.tested:
                # a test shared by two statements (suspend and watcher of an abort) is
                # decided once per instant, at its first use
                self.tested.add(number)
                self.events.append(("test", number, outcome))
            return outcome
        if kind is ir.SigNot:
            value = self.test(test.operand, scope, sure)
            return None if value is None else not value
        left = self.test(test.left, scope, sure)
        if kind is ir.SigAnd:
            if left is False:
                return False
            right = self.test(test.right, scope, sure and left is True)
            if right is False:
                return False
            return True if (left and right) else None
        if left is True:  # SigOr
            return True
        right = self.test(test.right, scope, sure and left is False)
        if right is True:
            return True
        return False if (left is False and right is False) else None

    # ------------------------------------------------------------------ the walk
    def go(self, node: KNode, depth: bool, sure: bool, scope: dict) -> tuple[int | None, int]:
        """Returns (must code or None, bitmask of codes the statement can return)."""
        kind = node.kind
        if kind == SEQ:
            return self._seq(node, depth, sure, scope)
        if kind == PAUSE:
            if depth:
                return 0, 1
            if sure:
                self.next.append(node.pid)
            return 1, 2
        if kind == EMIT:
            self._emit(node.src, sure, scope)
            return 0, 1
        if kind == PRESENT:
            return self._present(node, depth, sure, scope)
        if kind == LOOP:
            return self._loop(node, depth, sure, scope)
        if kind == PAR:
            return self._par(node, depth, sure, scope)
        if kind == TRAP:
            return self._trap(node, depth, sure, scope)
        if kind == EXIT:
            return node.code, 1 << node.code
        if kind == SUSPEND:
            return self._suspend(node, depth, sure, scope)
        if kind == ASSIGN:
            if sure:
                self.events.append(("assign", node.src.var, node.src.expr))
            return 0, 1
        if kind == LOCAL:
            inner = dict(scope)
            for decl in node.src.signals:
                inner[decl] = (decl, depth)
            return self.go(node.children[0], depth, sure, inner)
        if kind == MARK:
            return self.go(node.children[0], depth, sure, scope)
        assert kind == NOTHING
        return 0, 1

    def _emit(self, stmt: ir.Emit, sure: bool, scope: dict) -> None:
        key = scope.get(stmt.signal, stmt.signal)
        self.can.add(key)
        if sure:
            self.must.add(key)
            if stmt.value is not None:
                self.events.append(("emit", stmt.signal, stmt.value))

    def _seq(self, node: KNode, depth: bool, sure: bool, scope: dict):
        children = node.children
        start = 0
        codes = 0
        must: int | None = 0
        if depth:
            first = self.active[bisect_left(self.active, node.lo)]
            # the last child starting at or before that pause holds it (pause-less
            # children share their ``lo`` with the next child)
            start = bisect_right(node.child_los, first) - 1
            must, child_codes = self.go(children[start], True, sure, scope)
            codes = child_codes & ~1
            if not child_codes & 1:
                return (must if sure else None), codes
            sure = sure and must == 0
            start += 1
        for child in children[start:]:
            must, child_codes = self.go(child, False, sure, scope)
            codes |= child_codes & ~1
            if not child_codes & 1:
                return (must if sure else None), codes
            sure = sure and must == 0
        return (0 if sure else None), codes | 1

    def _present(self, node: KNode, depth: bool, sure: bool, scope: dict):
        then, orelse = node.children
        if depth:
            branch = then if self.selected(then) else orelse
            return self.go(branch, True, sure, scope)
        status = self.test(node.src.test, scope, sure)
        if status is True:
            return self.go(then, False, sure, scope)
        if status is False:
            return self.go(orelse, False, sure, scope)
        _, a = self.go(then, False, False, scope)
        _, b = self.go(orelse, False, False, scope)
        return None, a | b

    def _loop(self, node: KNode, depth: bool, sure: bool, scope: dict):
        body = node.children[0]
        must, codes = self.go(body, depth, sure, scope)
        if not (depth and codes & 1):
            return must, codes
        again_must, again = self.go(body, False, sure and must == 0, scope)
        if must == 0:
            result = again_must
        else:
            result = must if (sure and must is not None) else None
        return result, (codes & ~1) | again

    def _par(self, node: KNode, depth: bool, sure: bool, scope: dict):
        must: int | None = 0
        codes = 1
        for branch in node.children:
            if depth and not self.selected(branch):
                continue  # a branch that has terminated counts as terminated
            branch_must, branch_codes = self.go(branch, depth, sure, scope)
            # max_combine(codes, branch_codes) inlined and without loops: a code of one side
            # is a max iff it is ≥ the other side's smallest code (x & -x: lowest bit of x)
            if codes and branch_codes:
                codes = ((codes & -(branch_codes & -branch_codes))
                         | (branch_codes & -(codes & -codes)))
            else:
                codes = 0
            if must is not None:
                must = None if branch_must is None else max(must, branch_must)
        return (must if sure else None), codes

    def _trap(self, node: KNode, depth: bool, sure: bool, scope: dict):
        mark = len(self.next)
        must, codes = self.go(node.children[0], depth, sure, scope)
        own = node.code
        if must == own:
            del self.next[mark:]  # the exit kills the body: drop the pauses it reached
            must = 0
        if codes >> own & 1:
            codes = (codes & ~(1 << own)) | 1
        return must, codes

    def _suspend(self, node: KNode, depth: bool, sure: bool, scope: dict):
        body = node.children[0]
        if not depth:
            return self.go(body, False, sure, scope)
        status = self.test(node.src.test, scope, sure)
        if status is False:
            return self.go(body, True, sure, scope)
        if status is True:
            if sure:
                lo, hi = bisect_left(self.active, node.lo), bisect_left(self.active, node.hi)
                self.next.extend(self.active[lo:hi])
            return 1, 2
        _, codes = self.go(body, True, False, scope)
        return None, codes | 2


def react(prep: Prepared, state: tuple[int, ...] | None, oracle: Oracle) -> Outcome:
    """One reaction from ``state`` (``BOOT`` for the first instant) under ``oracle``."""
    env: dict = {}
    depth = state is not None
    active = state or ()
    while True:
        walk = _Walk(prep, active, oracle, env)
        must, _ = walk.go(prep.root, depth, True, {})
        if not walk.unknown:
            break
        progress = False
        for key in walk.unknown:
            if key in walk.must:
                env[key] = progress = True
            elif key not in walk.can:
                env[key] = False
                progress = True
        if not progress:
            _non_causal(walk)
    assert must is not None
    emitted = frozenset(k for k in walk.must if isinstance(k, ir.SignalDecl) and k.kind == ir.OUTPUT)
    _check_value_order(walk)
    return Outcome(tuple(walk.events), emitted, must, tuple(sorted(set(walk.next))))


def _non_causal(walk: _Walk):
    key, decl = next(iter(walk.unknown.items()))
    names = ", ".join(sorted({d.name for d in walk.unknown.values()}))
    raise OrccadError(
        f"non-causal program: the status of signal{'s' if ',' in names else ''} {names} "
        f"cannot be decided in this instant (it depends on itself)", walk.unknown_at[key])


def _reads(expr: ir.Expr, out: set) -> set:
    if isinstance(expr, ir.SigValue):
        out.add(expr.signal)
    elif isinstance(expr, ir.Unary):
        _reads(expr.operand, out)
    elif isinstance(expr, ir.Binary):
        _reads(expr.left, out)
        _reads(expr.right, out)
    elif isinstance(expr, ir.VectorExpr):
        for item in expr.items:
            _reads(item, out)
    return out


def _check_value_order(walk: _Walk) -> None:
    """``?S`` read before ``emit S(v)`` in the same instant would see a stale value."""
    emitters = {e[1] for e in walk.events if e[0] == "emit"}
    if not emitters:
        return
    done: set = set()
    for event in walk.events:
        if event[0] == "test":
            expr = walk.prep.data_tests[event[1]].expr
        else:
            expr = event[2]
        for signal in _reads(expr, set()) & emitters:
            if signal not in done:
                raise OrccadError(
                    f"non-causal program: the value of {signal.name} is read before it is "
                    "emitted in the same instant", getattr(expr, "loc", None))
        if event[0] == "emit":
            done.add(event[1])
