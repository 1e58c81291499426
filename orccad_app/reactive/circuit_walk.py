"""One symbolic walk of a prepared program (:mod:`.circuit`): each statement's visit as BDDs,
the engine's walk (:mod:`.walk`) for every state at once, with dual-rail (must, can) values."""

from __future__ import annotations

from orccad_app.diagnostics import SourceLocation
from orccad_app.reactive import ir
from orccad_app.reactive.prepare import (
    ASSIGN, EMIT, EXIT, LOCAL, LOOP, MARK, NOTHING, PAR, PAUSE, PRESENT, SEQ, SUSPEND, TRAP,
    KNode,
)
from orccad_app.reactive.bdd import Manager, Node
from orccad_app.reactive.circuit_data import Arithmetic, is_exact
from orccad_app.reactive.reads import fresh_pre, value_reads
from orccad_app.reactive.circuit import (Activation, Circuit, Rail, counter_bit, data_var,
                                         input_var, pre_bit, register)

__all__ = ["Walk", "merge_codes"]


class Walk:
    """One symbolic walk of the program for the current knowledge of signal statuses."""

    def __init__(self, circuit: Circuit, env: dict):
        self.c = circuit
        self.m = circuit.manager
        self.prep = circuit.prep
        self.env = env                       # signal key -> (present known, absent known)
        self.must: dict = {}
        self.can: dict = {}
        self.next: dict[int, Node] = {}      # pause -> sure next value
        self.fresh: dict = {}                # local decl -> where entered in surface (sure)
        self.frozen: list[tuple[KNode, Node]] = []
        self.evaluated: dict[int, Node] = {}
        self.undecided: list[tuple[Node, SourceLocation, str]] = []
        self.tested: set = set()             # signal keys some test reads
        self.arithmetic = Arithmetic(self.m)
        self.tracked = set(circuit.tracked)
        self.values = {v: [self.m.var(counter_bit(k, i)) for i in range(self.arithmetic.width)]
                       for k, v in enumerate(circuit.tracked)}
        self.constraints: Node = self.m.true  # exact data tests: their outcome is their value
        self.visit = 0                       # the current visit (Circuit.visit_id)
        self.node: KNode = circuit.prep.root  # the statement of the current visit
        self.activations: list[Activation] = []

    # ------------------------------------------------------------------ tests
    def test(self, test: ir.Test, scope: dict, act: Rail) -> Rail:
        """(known true, known false) of ``test``."""
        m = self.m
        kind = type(test)
        if kind is ir.SigRef:
            decl = test.signal
            if decl.kind == ir.INPUT:
                v = m.var(input_var(self.prep.program.inputs.index(decl)))
                return v, ~v
            key = scope.get(decl, decl)
            self.tested.add(key)
            present, absent = self.env.get(key, (m.false, m.false))
            self.undecided.append((act[1] & ~present & ~absent, test.loc, decl.name))
            return present, absent
        if kind is ir.DataTest:
            number = self.prep.data_test_index[id(test)]
            self.evaluated[number] = self.evaluated.get(number, m.false) | act[0]
            self.activations.append(Activation(
                "test", self.c.visit_id(self.visit, -1 - number, False), self.node, act[0],
                number, test.expr,
                reads=tuple(scope.get(d, d) for d in value_reads(test.expr, []))))
            v = m.var(data_var(number))
            if self.tracked and is_exact(test.expr, self.tracked):
                arithmetic = self.arithmetic
                value = arithmetic.truth(arithmetic.evaluate(test.expr, self.values, act[0]))
                self.constraints &= ~act[0] | v.equiv(value)
                return value, ~value
            return v, ~v
        if kind is ir.PreRef:
            key = scope.get(test.signal, test.signal)
            if type(key) is tuple and not key[1]:
                return m.false, m.true
            v = m.var(pre_bit(self.prep.pre_signals.index(test.signal)))
            return v, ~v
        if kind is ir.SigNot:
            t, f = self.test(test.operand, scope, act)
            return f, t
        lt, lf = self.test(test.left, scope, act)
        # the right operand is read only where the left one does not decide (the engine's
        # short circuit): its undecided status elsewhere is no causality error
        if kind is ir.SigAnd:
            rt, rf = self.test(test.right, scope, (act[0] & lt, act[1] & ~lf))
            return lt & rt, lf | rf
        rt, rf = self.test(test.right, scope, (act[0] & lf, act[1] & ~lt))
        return lt | rt, lf & rf

    # ------------------------------------------------------------------ statements
    def go(self, node: KNode, depth: bool, act: Rail, scope: dict) -> dict[int, Rail]:
        """The completion codes of one visit of ``node`` activated where ``act`` holds."""
        if act[1] == self.m.false:
            return {}
        visit, stmt = self.visit, self.node
        self.visit, self.node = self.c.visit_id(visit, node.index, depth), node
        try:
            return _GO[node.kind](self, node, depth, act, scope)
        finally:
            self.visit, self.node = visit, stmt

    def _record(self, kind: str, node: KNode, act: Rail, target, expr: ir.Expr | None,
                key, scope: dict) -> None:
        reads = () if expr is None else tuple(scope.get(d, d) for d in value_reads(expr, []))
        if expr is not None:
            expr = fresh_pre(self.prep, expr, scope)
        self.activations.append(Activation(kind, self.visit, node, act[0], target, expr, key,
                                           reads))

    def _pause(self, node, depth, act, scope):
        if depth:
            return {0: act}
        self.next[node.pid] = self.next.get(node.pid, self.m.false) | act[0]
        return {1: act}

    def _emit(self, node, depth, act, scope):
        key = scope.get(node.src.signal, node.src.signal)
        m = self.m
        self.must[key] = self.must.get(key, m.false) | act[0]
        self.can[key] = self.can.get(key, m.false) | act[1]
        if node.src.value is not None:
            self._record("emit", node, act, node.src.signal, node.src.value, key, scope)
        return {0: act}

    def _exit(self, node, depth, act, scope):
        return {node.code: act}

    def _instant(self, node, depth, act, scope):  # nothing
        return {0: act}

    def _assign(self, node, depth, act, scope):
        var = node.src.var
        if var in self.tracked:
            arithmetic = self.arithmetic
            new = arithmetic.vector(arithmetic.evaluate(node.src.expr, self.values, act[0]))
            self.values[var] = arithmetic.mux(act[0], new, self.values[var])
        self._record("assign", node, act, node.src.var, node.src.expr, None, scope)
        return {0: act}

    def _local(self, node, depth, act, scope):
        inner = dict(scope)
        for decl in node.src.signals:
            inner[decl] = (decl, depth)
            if not depth:
                self.fresh[decl] = self.fresh.get(decl, self.m.false) | act[0]
                if decl.valued and (decl.init is not None or node.in_loop):
                    self._record("init", node, act, decl, None, (decl, False), inner)
        child = node.children[0]
        return self.go(child, depth, act, inner)

    def _mark(self, node, depth, act, scope):
        return self.go(node.children[0], depth, act, scope)

    def _seq(self, node, depth, act, scope):
        m = self.m
        children = node.children
        codes: dict[int, Rail] = {}
        # the continuation into child j (from the depth of an earlier child, or the surface)
        carry: list[Rail] = [(m.false, m.false)] * (len(children) + 1)
        if depth:
            for k, child in enumerate(children):
                if child.lo == child.hi:
                    continue
                sel = self.c.selected(child.lo, child.hi)
                got = self.go(child, True, (act[0] & sel, act[1] & sel), scope)
                merge_codes(codes, got, skip=0)
                if 0 in got:
                    carry[k + 1] = got[0]
        else:
            carry[0] = act
        for j, child in enumerate(children):
            start = carry[j]
            if start[1] == m.false:
                continue
            got = self.go(child, False, start, scope)
            merge_codes(codes, got, skip=0)
            if 0 in got:
                nxt = carry[j + 1]
                carry[j + 1] = (nxt[0] | got[0][0], nxt[1] | got[0][1])
        end = carry[len(children)]
        if end[1] != m.false:
            merge_codes(codes, {0: end})
        return codes

    def _present(self, node, depth, act, scope):
        then, orelse = node.children
        if depth:
            sel = self.c.selected(then.lo, then.hi)
            codes = self.go(then, True, (act[0] & sel, act[1] & sel), scope)
            merge_codes(codes, self.go(orelse, True, (act[0] & ~sel, act[1] & ~sel), scope))
            return codes
        t, f = self.test(node.src.test, scope, act)
        codes = self.go(then, False, (act[0] & t, act[1] & ~f), scope)
        merge_codes(codes, self.go(orelse, False, (act[0] & f, act[1] & ~t), scope))
        return codes

    def _loop(self, node, depth, act, scope):
        body = node.children[0]
        codes = self.go(body, depth, act, scope)
        if not depth or 0 not in codes:
            return codes
        again = self.go(body, False, codes.pop(0), scope)
        merge_codes(codes, again)
        return codes

    def _par(self, node, depth, act, scope):
        m = self.m
        branches = []
        for branch in node.children:
            if depth:
                sel = self.c.selected(branch.lo, branch.hi)
                got = self.go(branch, True, (act[0] & sel, act[1] & sel), scope)
                dead = (act[0] & ~sel, act[1] & ~sel)
                merge_codes(got, {0: dead})
            else:
                got = self.go(branch, False, act, scope)
            branches.append(got)
        return _max_codes(m, act, branches)

    def _trap(self, node, depth, act, scope):
        before = dict(self.next)
        codes = self.go(node.children[0], depth, act, scope)
        own = node.code
        caught = codes.pop(own, None)
        if caught is None:
            return codes
        killed = caught[0]
        for pid in range(node.lo, node.hi):
            if pid in self.next:
                added = self.next[pid]
                old = before.get(pid, self.m.false)
                # the exit kills what this visit of the body reached, nothing else
                self.next[pid] = old | (added & ~old & ~killed)
        merge_codes(codes, {0: caught})
        return codes

    def _suspend(self, node, depth, act, scope):
        body = node.children[0]
        if not depth:
            return self.go(body, False, act, scope)
        t, f = self.test(node.src.test, scope, act)
        codes = self.go(body, True, (act[0] & f, act[1] & ~t), scope)
        stopped = act[0] & t
        if stopped != self.m.false:
            for pid in range(node.lo, node.hi):
                keep = stopped & self.m.var(register(pid))
                self.next[pid] = self.next.get(pid, self.m.false) | keep
            self.frozen.append((node, stopped))
        merge_codes(codes, {1: (act[0] & t, act[1] & ~f)})
        return codes


def merge_codes(codes: dict[int, Rail], other: dict[int, Rail], skip: int | None = None) -> None:
    for code, (sure, may) in other.items():
        if code == skip:
            continue
        if code in codes:
            a, b = codes[code]
            codes[code] = (a | sure, b | may)
        else:
            codes[code] = (sure, may)


def _max_codes(m: Manager, act: Rail, branches: list[dict[int, Rail]]) -> dict[int, Rail]:
    """The completion of a ``par``: the max of its branches' codes (dual rail).

    Sure code c: every branch's code is sure and at most c, one is c. Possible code c: one
    branch may return c and every branch may return a code at most c."""
    codes = sorted({c for b in branches for c in b})
    result: dict[int, Rail] = {}
    for c in codes:
        all_sure_le, all_may_le = m.true, m.true
        one_sure, one_may = m.false, m.false
        for b in branches:
            all_sure_le &= m.any(b[k][0] for k in b if k <= c)
            all_may_le &= m.any(b[k][1] for k in b if k <= c)
            if c in b:
                one_sure |= b[c][0]
                one_may |= b[c][1]
        sure = all_sure_le & one_sure & act[0]
        may = all_may_le & one_may
        if may != m.false:
            result[c] = (sure, may)
    return result


_GO: list = [None] * 13
for _kind, _handler in ((SEQ, Walk._seq), (PAUSE, Walk._pause), (EMIT, Walk._emit),
                        (PRESENT, Walk._present), (LOOP, Walk._loop), (PAR, Walk._par),
                        (TRAP, Walk._trap), (EXIT, Walk._exit), (SUSPEND, Walk._suspend),
                        (ASSIGN, Walk._assign), (LOCAL, Walk._local), (MARK, Walk._mark),
                        (NOTHING, Walk._instant)):
    _GO[_kind] = _handler
