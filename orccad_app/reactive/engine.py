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


class _Values:
    """What the walks of one reaction share about values (see :func:`react`).

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


class _Walk:
    """Mutable scratch of one walk over the program."""

    __slots__ = ("prep", "active", "oracle", "env", "must", "can", "unknown", "unknown_at",
                 "events", "next", "tested", "values", "unready", "blocked", "fresh",
                 "occurrences", "active_set", "deferred_vars", "old_reads", "deferred_keys",
                 "frozen", "before")

    def __init__(self, prep: Prepared, active: tuple[int, ...], oracle: Oracle, env: dict,
                 values: _Values):
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
        reads = _reads(expr, [], self.deferred_vars)
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
        self.blocked.extend((key, loc) for key in waiting if not _is_var(key))

    def read_keys(self, expr: ir.Expr, scope: dict) -> tuple:
        return tuple(scope.get(decl, decl) for decl in _reads(expr, []))

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
            number = self.prep.data_test_index[id(test)]
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
        self.record(node.index, ("assign", stmt.var, _fresh_pre(self.prep, stmt.expr, scope),
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
        self.record(node.index, ("emit", stmt.signal, _fresh_pre(self.prep, stmt.value, scope),
                                 key, self.read_keys(stmt.value, scope), stmt.loc))
        return True

    def _constructive(self, key, stmt: ir.Emit) -> None:
        """Esterel v5 rejects a value read before, in sequence, an emission of its signal in
        the same instant: the read waits for every emission, which waits for the read."""
        for waiting, loc in self.before:
            if waiting == key:
                name = stmt.signal.name
                raise OrccadError(
                    f"non-constructive program: ?{name} is read here before an emission of "
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


#: The walk's handler of each statement kind (see :meth:`_Walk.go`).
_GO: list = [None] * 13
for _kind, _handler in ((SEQ, _Walk._seq), (PAUSE, _Walk._pause), (EMIT, _Walk._emit_stmt),
                        (PRESENT, _Walk._present), (LOOP, _Walk._loop), (PAR, _Walk._par),
                        (TRAP, _Walk._trap), (EXIT, _Walk._exit), (SUSPEND, _Walk._suspend),
                        (ASSIGN, _Walk._assign), (LOCAL, _Walk._local), (MARK, _Walk._mark),
                        (NOTHING, _Walk._nothing)):
    _GO[_kind] = _handler
assert None not in _GO

#: Walks allowed for one reaction (each walk decides at least one status or value).
MAX_WALKS = 10_000


def react(prep: Prepared, state: tuple[int, ...] | None, oracle: Oracle) -> Outcome:
    """One reaction from ``state`` (``BOOT`` for the first instant) under ``oracle``."""
    env: dict = {}
    depth = state is not None
    active = state or ()
    values = _Values()
    while True:
        walk = _Walk(prep, active, oracle, env, values)
        must, _ = walk.go(prep.root, depth, True, {})
        if not walk.unknown and not walk.blocked:
            break
        progress = False
        for key in walk.unknown:
            if key in walk.must:
                env[key] = progress = True
            elif key not in walk.can:
                env[key] = False
                progress = True
        if values.not_ready is None or walk.unready != values.not_ready:
            progress = True
        values.not_ready = walk.unready
        if len(walk.events) > values.sure_events:
            values.sure_events = len(walk.events)
            progress = True
        values.round += 1
        if not progress or values.round > MAX_WALKS:
            if walk.unknown:
                _non_causal(walk)
            key, loc = walk.blocked[0]
            name = key[0].name if type(key) is tuple else key.name
            raise OrccadError(f"non-causal program: the value of {name} is read in an instant "
                              "where its emission depends on that read", loc)
    assert must is not None
    emitted = frozenset(k for k in walk.must if isinstance(k, ir.SignalDecl) and k.kind == ir.OUTPUT)
    events = _schedule(prep, walk)
    state_out = sorted(set(walk.next))
    for k, decl in enumerate(prep.pre_signals):
        if decl.kind == ir.INPUT:
            present = oracle.input(decl)
        elif decl.kind == ir.LOCAL:
            present = (decl, decl not in walk.fresh) in walk.must
            if _suspended(prep, walk, decl):  # its previous instant is its last one running
                present = prep.pre_base + k in walk.active_set
        else:
            present = decl in walk.must
        if present:
            state_out.append(prep.pre_base + k)
    return Outcome(events, emitted, must, tuple(state_out))


def _suspended(prep: Prepared, walk: _Walk, decl: ir.SignalDecl) -> bool:
    """The declaration of the local ``decl`` is alive inside a suspend frozen in this instant
    (Esterel v5: ``pre(S)`` of a local refers to the previous instant its scope ran)."""
    for index, lo, hi in prep.local_nodes.get(decl, ()):
        if lo == hi or bisect_left(walk.active, hi) == bisect_left(walk.active, lo):
            continue  # no pause inside: not alive across instants
        for frozen_index, frozen_lo, frozen_hi in walk.frozen:
            if frozen_index < index and frozen_lo <= lo and hi <= frozen_hi:
                return True
    return False


def _non_causal(walk: _Walk):
    key, decl = next(iter(walk.unknown.items()))
    names = ", ".join(sorted({d.name for d in walk.unknown.values()}))
    raise OrccadError(
        f"non-causal program: the status of signal{'s' if ',' in names else ''} {names} "
        f"cannot be decided in this instant (it depends on itself)", walk.unknown_at[key])


def _is_var(key) -> bool:
    return type(key) is tuple and key[0] == "var"


def _reads(expr: ir.Expr, out: list, variables: set = frozenset()) -> list:
    """The signals whose value (``?S``, not ``pre(?S)``) ``expr`` reads, and
    ``("var", v)`` for the variables of ``variables`` it reads."""
    kind = type(expr)
    if kind is ir.SigValue:
        out.append(expr.signal)
    elif kind is ir.VarRef:
        if expr.var in variables:
            out.append(("var", expr.var))
    elif kind is ir.Unary:
        _reads(expr.operand, out, variables)
    elif kind is ir.Binary:
        _reads(expr.left, out, variables)
        _reads(expr.right, out, variables)
    elif kind is ir.VectorExpr:
        for item in expr.items:
            _reads(item, out, variables)
    return out


def _fresh_pre(prep: Prepared, expr: ir.Expr, scope: dict) -> ir.Expr:
    """``expr`` with ``pre(?S)`` of a local signal in its first instant (a fresh incarnation)
    replaced by S's initial value: the fresh signal has no past (Esterel v5)."""
    fresh = [d for d, key in scope.items() if type(key) is tuple and not key[1]]
    if not fresh or not _has_pre(expr, fresh):
        return expr
    return _made(prep, ("fresh", id(expr), tuple(id(d) for d in fresh)),
                 lambda: _substitute_pre(expr, fresh))


def _has_pre(expr: ir.Expr, decls: list) -> bool:
    kind = type(expr)
    if kind is ir.PreValue:
        return expr.signal in decls
    if kind is ir.Unary:
        return _has_pre(expr.operand, decls)
    if kind is ir.Binary:
        return _has_pre(expr.left, decls) or _has_pre(expr.right, decls)
    if kind is ir.VectorExpr:
        return any(_has_pre(i, decls) for i in expr.items)
    return False


def _substitute_pre(expr: ir.Expr, decls: list) -> ir.Expr:
    kind = type(expr)
    if kind is ir.PreValue and expr.signal in decls:
        if expr.signal.init is None:
            return ir.Fault(f"pre(?{expr.signal.name}) is read in the first instant of local "
                            f"signal {expr.signal.name}, which has no initial value", expr.loc)
        return ir.Const(expr.signal.init, expr.loc)
    if kind is ir.Unary:
        return ir.Unary(expr.op, _substitute_pre(expr.operand, decls), expr.loc)
    if kind is ir.Binary:
        return ir.Binary(expr.op, _substitute_pre(expr.left, decls),
                         _substitute_pre(expr.right, decls), expr.loc)
    if kind is ir.VectorExpr:
        return ir.VectorExpr(tuple(_substitute_pre(i, decls) for i in expr.items), expr.loc)
    return expr


def _made(prep: Prepared, key: tuple, make):
    found = prep.made.get(key)
    if found is None:
        found = prep.made[key] = make()
    return found


def _schedule(prep: Prepared, walk: _Walk) -> tuple:
    """The instant's run-time events in execution order (see :class:`_Values`).

    A second emission of a valued signal combines with the first (``combine``); without
    ``combine`` it is a compile error when no data test of the instant could rule it out, and
    otherwise a :class:`~orccad_app.reactive.ir.Fault` raised at run time if it happens.
    """
    ordered = [event for _, event in sorted(walk.events, key=lambda e: e[0])]
    first_at: dict = {}
    written: set = set()
    tested = False
    out: list = []
    for kind, target, expr, key, reads, loc in ordered:
        for read in reads:
            if type(read) is tuple and read[1] and (read[0], False) in written:
                raise OrccadError(
                    f"the value of the previous incarnation of local signal {read[0].name} is "
                    "read after its new incarnation was given a value in the same instant "
                    "(not supported: read it before the loop restarts)", loc)
        if kind == "test":
            tested = True
            out.append(("test", target, expr))
        elif kind == "assign":
            out.append(("assign", target, expr))
        elif kind == "init":
            written.add(key)
            value = _made(prep, ("init", target), lambda: ir.Const(
                ir.NO_VALUE if target.init is None else target.init, loc))
            out.append(("emit", target, value))
        else:
            written.add(key)
            if key not in first_at:
                first_at[key] = loc
                out.append(("emit", target, expr))
            elif target.combine is not None:
                out.append(("emit", target, _made(prep, ("combine", id(expr)), lambda: ir.Binary(
                    target.combine, ir.SigValue(target, loc), expr, loc))))
            elif tested:
                message = (f"signal {target.name} is emitted twice in one instant (first at "
                           f"{first_at[key]}) and declares no 'combine'")
                out.append(("emit", target, _made(prep, ("fault", id(expr)),
                                                  lambda: ir.Fault(message, loc))))
            else:
                raise OrccadError(
                    f"signal {target.name} is emitted twice in one instant (first at "
                    f"{first_at[key]}): declare how its values combine, e.g. "
                    f"'output {target.name} : {target.type} combine +;'", loc)
    return tuple(out)
