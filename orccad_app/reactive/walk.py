"""The walk: one pass over a prepared program, for the current knowledge of an instant.

A walk goes through the program in *surface* mode (statements started in this instant) or
*depth* mode (statements resumed from an active pause) and returns, for each statement, the
completion code it *must* return (or None when not sure) and the codes it *can* return. On the
way it collects what must and what can be emitted, the signals tested while their status is
unknown, the reads of values that have to wait, the data events that are sure (with their
order keys) and the next control state. :func:`.engine.react` repeats walks until every tested
signal and every read value is known; the decisions are in :mod:`.engine`.
"""

from __future__ import annotations

from bisect import bisect_left, bisect_right
from typing import Protocol

from orccad_app.diagnostics import OrccadError
from orccad_app.reactive import ir
from orccad_app.reactive.prepare import (
    ASSIGN, EMIT, EXIT, LOCAL, LOOP, MARK, NOTHING, PAR, PAUSE, PRESENT, SEQ, SUSPEND, TRAP,
    KNode, Prepared,
)
from orccad_app.reactive.reads import fresh_pre, fresh_test, is_var, value_reads

__all__ = ["Oracle", "Values", "Walk"]


class Oracle(Protocol):
    """Decides what the program's inputs and data are, when the engine asks."""

    def input(self, signal: ir.SignalDecl) -> bool: ...
    def data(self, number: int) -> bool: ...



class Values:
    """What the walks of one reaction share about values (see :func:`.engine.react`).

    ``not_ready`` holds the signal keys whose value may still change in this instant (an
    emission of them is not yet sure, or waits for a value itself); ``None`` before the first
    walk, when every signal with a valued emission counts as not ready. ``first_round`` gives
    each data event (by node and occurrence) the walk where it first became sure and ready:
    events are performed in that order, so a read of ``?S`` comes after every emission of S of
    the instant, whatever parallel branch holds it.
    """

    __slots__ = ("round", "not_ready", "first_round", "sure_events")

    def __init__(self) -> None:
        self.round = 0
        self.not_ready: set | None = None
        self.first_round: dict = {}
        self.sure_events = 0


class Walk:
    """Mutable scratch of one walk over the program."""

    __slots__ = ("prep", "active", "oracle", "env", "must", "can", "unknown", "unknown_at",
                 "events", "next", "tested", "values", "unready", "blocked", "fresh",
                 "occurrences", "active_set", "deferred_vars", "old_reads", "deferred_keys",
                 "frozen", "before")

    def __init__(self, prep: Prepared, active: tuple[int, ...], oracle: Oracle, env: dict,
                 values: Values):
        self.prep = prep
        self.active = active
        self.active_set = frozenset(active) if prep.pre_signals else frozenset()
        self.oracle = oracle
        self.env = env
        self.must: set = set()
        self.can: set = set()
        self.unknown: dict = {}
        self.unknown_at: dict = {}
        self.events: list = []
        self.next: list[int] = []
        self.tested: set[int] = set()
        self.values = values
        self.unready: set = set()     # keys with an emission not sure or not ready yet
        self.blocked: list = []       # (signal key, location) of reads that had to wait
        self.fresh: set = set()       # local signals entered in surface mode (sure)
        self.frozen: list = []        # (index, lo, hi) of each suspend frozen in the instant
        self.before: list = []        # (key, loc) of the reads waiting earlier in sequence
        self.occurrences: dict = {}
        self.deferred_vars: set = set()  # variables whose assignment waits for a value
        self.old_reads: set = set()      # locals whose old incarnation has a read waiting
        self.deferred_keys: set = set()  # new incarnations waiting for those reads

    # ------------------------------------------------------------------ helpers
    def selected(self, node: KNode) -> bool:
        active = self.active
        i = bisect_left(active, node.lo)
        return i < len(active) and active[i] < node.hi

    def missing(self, expr: ir.Expr, scope: dict) -> list:
        """What ``expr`` reads that is not final yet: signal keys, and variables whose
        assignment waits (as ``("var", decl)``)."""
        found: list = []
        reads = value_reads(expr, [], self.deferred_vars)
        for decl in reads:
            if type(decl) is tuple:
                found.append(decl)
            elif decl in self.prep.valued_emitted:
                key = scope.get(decl, decl)
                not_ready = self.values.not_ready
                if not_ready is None or key in not_ready:
                    found.append(key)
                    if type(key) is tuple and key[1]:
                        self.old_reads.add(decl)
        return found

    def block(self, waiting: list, loc) -> None:
        self.blocked.extend((key, loc) for key in waiting if not is_var(key))

    def read_keys(self, expr: ir.Expr, scope: dict) -> tuple:
        return tuple(scope.get(decl, decl) for decl in value_reads(expr, []))

    def record(self, occurrence, event: tuple) -> None:
        """A sure data event; its order key is (first walk it was sure in, walk position)."""
        n = self.occurrences.get(occurrence, 0)
        self.occurrences[occurrence] = n + 1
        first = self.values.first_round.setdefault((occurrence, n), self.values.round)
        self.events.append(((first, len(self.events)), event))

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
            waiting = self.missing(test.expr, scope)
            if waiting:
                self.block(waiting, test.loc)
                return None
            number = fresh_test(self.prep, test, scope)
            if type(number) is bool:  # pre(?S) of a fresh local, and nothing else, read
                return number
            outcome = self.oracle.data(number)
            if sure and number not in self.tested:
                # a test shared by two statements (suspend and watcher of an abort) is
                # decided once per instant, at its first use
                self.tested.add(number)
                self.record(("test", number), ("test", number, outcome, None,
                                               self.read_keys(test.expr, scope), test.loc))
            return outcome
        if kind is ir.PreRef:
            key = scope.get(test.signal, test.signal)
            if type(key) is tuple and not key[1]:
                return False  # a fresh incarnation of a local signal has no past
            bit = self.prep.pre_base + self.prep.pre_signals.index(test.signal)
            return bit in self.active_set
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
        """Returns (must code or None, bitmask of codes the statement can return).

        The walk's own recursion calls ``_GO[kind]`` directly (one Python call per statement
        instead of two: the walk is the compiler's hot loop)."""
        return _GO[node.kind](self, node, depth, sure, scope)

    def _pause(self, node: KNode, depth: bool, sure: bool, scope: dict):
        if depth:
            return 0, 1
        if sure:
            self.next.append(node.pid)
        return 1, 2

    def _emit_stmt(self, node: KNode, depth: bool, sure: bool, scope: dict):
        self._emit(node, sure, scope)
        return 0, 1

    def _exit(self, node: KNode, depth: bool, sure: bool, scope: dict):
        return node.code, 1 << node.code

    def _assign(self, node: KNode, depth: bool, sure: bool, scope: dict):
        if not sure:
            return None, 1
        stmt = node.src
        waiting = self.missing(stmt.expr, scope)
        if waiting or stmt.var in self.deferred_vars:
            # the assignment waits for a value; what reads the variable waits for it
            self.block(waiting, stmt.loc)
            self.deferred_vars.add(stmt.var)
            return 0, 1
        self.record(node.index, ("assign", stmt.var, fresh_pre(self.prep, stmt.expr, scope),
                                 None, self.read_keys(stmt.expr, scope), stmt.loc))
        return 0, 1

    def _local(self, node: KNode, depth: bool, sure: bool, scope: dict):
        inner = dict(scope)
        for decl in node.src.signals:
            inner[decl] = (decl, depth)
            if not depth and sure:
                self.fresh.add(decl)
                if decl in self.old_reads:
                    # the old incarnation's value is still to be read in this instant
                    self.deferred_keys.add((decl, False))
                    self.unready.add((decl, False))
                elif decl.valued and (decl.init is not None or node.in_loop):
                    # a new incarnation: ?S starts from the initial value (or none)
                    self.record(node.index, ("init", decl, None, (decl, False), (),
                                             node.src.loc))
        child = node.children[0]
        return _GO[child.kind](self, child, depth, sure, inner)

    def _mark(self, node: KNode, depth: bool, sure: bool, scope: dict):
        child = node.children[0]
        return _GO[child.kind](self, child, depth, sure, scope)

    def _nothing(self, node: KNode, depth: bool, sure: bool, scope: dict):
        return 0, 1

    def _emit(self, node: KNode, sure: bool, scope: dict) -> bool:
        """Emits; False when the value must wait for another value of the instant."""
        stmt = node.src
        key = scope.get(stmt.signal, stmt.signal)
        self.can.add(key)
        if sure:
            self.must.add(key)
            if self.before:
                self._constructive(key, stmt)
        if stmt.value is None:
            return True
        if not sure or key in self.deferred_keys:
            self.unready.add(key)
            return True
        waiting = self.missing(stmt.value, scope)
        if waiting:
            self.unready.add(key)
            self.block(waiting, stmt.loc)
            return True
        self.record(node.index, ("emit", stmt.signal, fresh_pre(self.prep, stmt.value, scope),
                                 key, self.read_keys(stmt.value, scope), stmt.loc))
        return True

    def _constructive(self, key, stmt: ir.Emit) -> None:
        """Esterel v5 rejects a value read before, in sequence, an emission of its signal in
        the same instant: the read waits for every emission, which waits for the read."""
        for waiting, loc in self.before:
            if waiting == key:
                name = stmt.signal.name
                raise OrccadError(
                    f"non-causal program: ?{name} is read here before an emission of "
                    f"{name} that follows it in the same instant (line {stmt.loc.line}); "
                    f"emit {name} first, or read pre(?{name}) for its previous value", loc)

    def _seq(self, node: KNode, depth: bool, sure: bool, scope: dict):
        saved = len(self.before)
        try:
            return self._seq_children(node, depth, sure, scope)
        finally:
            del self.before[saved:]

    def _seq_children(self, node: KNode, depth: bool, sure: bool, scope: dict):
        """:meth:`_seq`; the reads that wait in a child precede the next children."""
        children = node.children
        before, blocked = self.before, self.blocked
        start = 0
        codes = 0
        must: int | None = 0
        if depth:
            first = self.active[bisect_left(self.active, node.lo)]
            # the last child starting at or before that pause holds it (pause-less
            # children share their ``lo`` with the next child)
            start = bisect_right(node.child_los, first) - 1
            child = children[start]
            mark = len(blocked)
            must, child_codes = _GO[child.kind](self, child, True, sure, scope)
            if len(blocked) > mark:
                before.extend(blocked[mark:])
            codes = child_codes & ~1
            if not child_codes & 1:
                return (must if sure else None), codes
            sure = sure and must == 0
            start += 1
        for index in range(start, len(children)):  # no slice: a mission's top sequence is long
            child = children[index]
            mark = len(blocked)
            must, child_codes = _GO[child.kind](self, child, False, sure, scope)
            if len(blocked) > mark:
                before.extend(blocked[mark:])
            codes |= child_codes & ~1
            if not child_codes & 1:
                return (must if sure else None), codes
            sure = sure and must == 0
        return (0 if sure else None), codes | 1

    def _present(self, node: KNode, depth: bool, sure: bool, scope: dict):
        then, orelse = node.children
        if depth:
            branch = then if self.selected(then) else orelse
            return _GO[branch.kind](self, branch, True, sure, scope)
        status = self.test(node.src.test, scope, sure)
        if status is True:
            return _GO[then.kind](self, then, False, sure, scope)
        if status is False:
            return _GO[orelse.kind](self, orelse, False, sure, scope)
        _, a = _GO[then.kind](self, then, False, False, scope)
        _, b = _GO[orelse.kind](self, orelse, False, False, scope)
        return None, a | b

    def _loop(self, node: KNode, depth: bool, sure: bool, scope: dict):
        body = node.children[0]
        mark, saved = len(self.blocked), len(self.before)
        must, codes = _GO[body.kind](self, body, depth, sure, scope)
        if not (depth and codes & 1):
            return must, codes
        self.before.extend(self.blocked[mark:])  # the first pass precedes the second
        again_must, again = _GO[body.kind](self, body, False, sure and must == 0, scope)
        del self.before[saved:]
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
            branch_must, branch_codes = _GO[branch.kind](self, branch, depth, sure, scope)
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
        body = node.children[0]
        must, codes = _GO[body.kind](self, body, depth, sure, scope)
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
            return _GO[body.kind](self, body, False, sure, scope)
        status = self.test(node.src.test, scope, sure)
        if status is False:
            return _GO[body.kind](self, body, True, sure, scope)
        if status is True:
            if sure:
                lo, hi = bisect_left(self.active, node.lo), bisect_left(self.active, node.hi)
                self.next.extend(self.active[lo:hi])
                self.frozen.append((node.index, node.lo, node.hi))
            return 1, 2
        _, codes = _GO[body.kind](self, body, True, False, scope)
        return None, codes | 2


#: The walk's handler of each statement kind (see :meth:`Walk.go`).
_GO: list = [None] * 13
for _kind, _handler in ((SEQ, Walk._seq), (PAUSE, Walk._pause), (EMIT, Walk._emit_stmt),
                        (PRESENT, Walk._present), (LOOP, Walk._loop), (PAR, Walk._par),
                        (TRAP, Walk._trap), (EXIT, Walk._exit), (SUSPEND, Walk._suspend),
                        (ASSIGN, Walk._assign), (LOCAL, Walk._local), (MARK, Walk._mark),
                        (NOTHING, Walk._nothing)):
    _GO[_kind] = _handler
assert None not in _GO
