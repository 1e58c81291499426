"""The circuit of a reactive program: its instant as boolean functions, evaluated on BDDs.

Esterel v5's translation (Berry, *The Constructive Semantics of Pure Esterel*, ch. 11–12):
one register per ``pause`` and per signal whose ``pre`` is read, and, for the instant, a
wire per statement activation, completion code and signal. The wires are built by walking
the prepared kernel (:mod:`orccad_app.reactive.prepare`) the way the explicit engine walks it
(:mod:`orccad_app.reactive.walk`), statement by statement, but with BDDs over the registers,
the inputs and the data tests instead of one state and one valuation:

- every *visit* of a statement (its surface, started in the instant, or its depth, resumed
  from its registers; a loop's body is visited in depth and again in surface when it
  restarts; a sequence's later children once as the continuation of its depth) has its own
  wires, so a statement run twice in one instant (a loop restarted by an enclosing one, the
  old and the new incarnation of a local signal) is two sub-circuits, as the engine walks it
  twice: the circuit is the engine's instant, tabulated for all states at once;
- values are *dual rail*: a pair (must, can) of BDDs, as the engine's must/can analysis.
  Signal statuses are the least fixpoint of the walks (present where they must be emitted,
  absent where they cannot be); the program is constructive where every signal a test reads
  is decided; where it is not, in a reachable state, the program is refused (located at the
  test), as the explicit compiler refuses it;
- data tests are free variables, one per test and instant (the checker's data abstraction),
  and data actions are not evaluated: this circuit is the control of the program. Where each
  data action and data test is reached is recorded (:class:`Activation`, in the walk's order,
  with its sure activation in every walk) for the C generator, which runs them
  (:mod:`orccad_app.codegen.circuit_schedule`).

The result (:class:`Circuit`) gives the next value of every register, the outputs emitted,
the completion of the program and what the checker's atoms and fairness sets read.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from orccad_app.diagnostics import SourceLocation
from orccad_app.reactive import ir
from orccad_app.reactive.prepare import (
    ASSIGN, EMIT, EXIT, LOCAL, LOOP, MARK, NOTHING, PAR, PAUSE, PRESENT, SEQ, SUSPEND, TRAP,
    KNode, Prepared,
)
from orccad_app.reactive.bdd import Manager, Node
from orccad_app.reactive.circuit_data import WIDTH, Arithmetic, is_exact
from orccad_app.reactive.reads import fresh_pre, value_reads

__all__ = ["Activation", "Circuit", "build_circuit", "register", "pre_bit", "input_var", "data_var",
           "BOOT", "TERM", "FAILED_BEFORE", "next_name", "MAX_FIXPOINT_WALKS"]

BOOT, TERM, FAILED_BEFORE = "boot", "term", "failed_before"
#: Walks allowed to reach the signals' fixpoint (each decides at least one more status).
MAX_FIXPOINT_WALKS = 2_000


def register(pid: int) -> str:
    return f"r{pid}"


def pre_bit(k: int) -> str:
    return f"q{k}"


def input_var(index: int) -> str:
    return f"i{index}"


def data_var(number: int) -> str:
    return f"d{number}"


def counter_bit(k: int, bit: int) -> str:
    """Bit ``bit`` of the ``k``-th tracked variable's register."""
    return f"v{k}_{bit}"


def next_name(name: str) -> str:
    return name + "_n"


Rail = tuple[Node, Node]
"""A dual-rail value: (where it is sure, where it may be)."""


@dataclass
class Activation:
    """One visit of a data action or data test in the walk (what the engine records as an
    event, :meth:`orccad_app.reactive.walk.Walk.record`).

    ``kind``: ``assign``, ``emit`` (a valued emission), ``init`` (a valued local signal's new
    incarnation) or ``test``; ``visit`` numbers the visit (the same in every walk), ``node``
    is the statement (for a test: the statement whose test reads it), ``sure`` where it runs;
    ``target`` the variable, signal or data-test number; ``expr`` the expression (a signal's
    ``pre`` in its fresh incarnation already replaced, as the engine does); ``key`` the
    signal's incarnation (locals: ``(decl, depth)``); ``reads`` the incarnations whose value
    it reads.
    """

    kind: str
    visit: int
    node: KNode
    sure: Node
    target: object
    expr: ir.Expr | None
    key: object = None
    reads: tuple = ()


@dataclass
class Circuit:
    """The instant of a program as functions of the registers, inputs and data tests.

    Every function holds only where the program has not terminated (``term`` false).
    ``next`` gives each register's next value (registers: ``boot``, ``term``,
    ``failed_before``, pauses, ``pre`` bits), ``emitted`` each output's presence, ``code0``
    where the program terminates in the instant, ``evaluated`` where each data test is
    evaluated, ``undecided`` where a signal test cannot be decided (with the test's location),
    ``frozen`` nothing (kept for the reader of the walk).
    """

    prep: Prepared
    manager: Manager
    registers: list[str]
    inputs: list[str]
    data: list[str]
    next: dict[str, Node] = field(default_factory=dict)
    emitted: dict[ir.SignalDecl, Node] = field(default_factory=dict)
    code0: Node = None
    evaluated: dict[int, Node] = field(default_factory=dict)
    undecided: list[tuple[Node, SourceLocation, str]] = field(default_factory=list)
    relations: Node = None
    walks: int = 0
    tracked: tuple[ir.VarDecl, ...] = ()
    overflow: Node = None
    """Where a tracked variable's value leaves its bits (the counters are then abstracted)."""
    #: the data actions and tests of the last walk, in its order
    activations: list[Activation] = field(default_factory=list)
    #: for each walk, the sure activation of each visit (by ``Activation.visit``)
    activation_rounds: list[dict[int, Node]] = field(default_factory=list)
    _visits: dict[tuple, int] = field(default_factory=dict)

    def visit_id(self, parent: int, index: int, depth: bool) -> int:
        """The number of the visit of statement ``index`` (in depth or not) inside visit
        ``parent``: the same in every walk."""
        key = (parent, index, depth)
        number = self._visits.get(key)
        if number is None:
            number = self._visits[key] = len(self._visits) + 1
        return number

    def selected(self, lo: int, hi: int) -> Node:
        """Where a current register of the pauses ``[lo, hi)`` is set."""
        m = self.manager
        return m.any(m.var(register(p)) for p in range(lo, hi))

    def selected_next(self, lo: int, hi: int) -> Node:
        """Where a register of the pauses ``[lo, hi)`` is set after the instant."""
        return self.manager.any(self.next[register(p)] for p in range(lo, hi))


class _Walk:
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
                _merge(codes, got, skip=0)
                if 0 in got:
                    carry[k + 1] = got[0]
        else:
            carry[0] = act
        for j, child in enumerate(children):
            start = carry[j]
            if start[1] == m.false:
                continue
            got = self.go(child, False, start, scope)
            _merge(codes, got, skip=0)
            if 0 in got:
                nxt = carry[j + 1]
                carry[j + 1] = (nxt[0] | got[0][0], nxt[1] | got[0][1])
        end = carry[len(children)]
        if end[1] != m.false:
            _merge(codes, {0: end})
        return codes

    def _present(self, node, depth, act, scope):
        then, orelse = node.children
        if depth:
            sel = self.c.selected(then.lo, then.hi)
            codes = self.go(then, True, (act[0] & sel, act[1] & sel), scope)
            _merge(codes, self.go(orelse, True, (act[0] & ~sel, act[1] & ~sel), scope))
            return codes
        t, f = self.test(node.src.test, scope, act)
        codes = self.go(then, False, (act[0] & t, act[1] & ~f), scope)
        _merge(codes, self.go(orelse, False, (act[0] & f, act[1] & ~t), scope))
        return codes

    def _loop(self, node, depth, act, scope):
        body = node.children[0]
        codes = self.go(body, depth, act, scope)
        if not depth or 0 not in codes:
            return codes
        again = self.go(body, False, codes.pop(0), scope)
        _merge(codes, again)
        return codes

    def _par(self, node, depth, act, scope):
        m = self.m
        branches = []
        for branch in node.children:
            if depth:
                sel = self.c.selected(branch.lo, branch.hi)
                got = self.go(branch, True, (act[0] & sel, act[1] & sel), scope)
                dead = (act[0] & ~sel, act[1] & ~sel)
                _merge(got, {0: dead})
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
        _merge(codes, {0: caught})
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
        _merge(codes, {1: (act[0] & t, act[1] & ~f)})
        return codes


def _merge(codes: dict[int, Rail], other: dict[int, Rail], skip: int | None = None) -> None:
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
for _kind, _handler in ((SEQ, _Walk._seq), (PAUSE, _Walk._pause), (EMIT, _Walk._emit),
                        (PRESENT, _Walk._present), (LOOP, _Walk._loop), (PAR, _Walk._par),
                        (TRAP, _Walk._trap), (EXIT, _Walk._exit), (SUSPEND, _Walk._suspend),
                        (ASSIGN, _Walk._assign), (LOCAL, _Walk._local), (MARK, _Walk._mark),
                        (NOTHING, _Walk._instant)):
    _GO[_kind] = _handler


# --------------------------------------------------------------------------- building

def _declare(m: Manager, prep: Prepared, tracked: tuple[ir.VarDecl, ...]
             ) -> tuple[list[str], list[str], list[str]]:
    """Declare the variables in program order: each register beside its next copy, each
    input and data test at its first test."""
    registers: list[str] = []
    inputs: list[str] = []
    data: list[str] = []

    def reg(name: str) -> None:
        m.declare(name)
        m.declare(next_name(name))
        registers.append(name)

    for name in (BOOT, TERM, FAILED_BEFORE):
        reg(name)
    for k in range(len(tracked)):
        for bit in range(WIDTH):
            reg(counter_bit(k, bit))
    program = prep.program

    def tests(test: ir.Test) -> None:
        if isinstance(test, ir.SigRef) and test.signal.kind == ir.INPUT:
            name = input_var(program.inputs.index(test.signal))
            if not m.has(name):
                m.declare(name)
                inputs.append(name)
        elif isinstance(test, ir.DataTest):
            name = data_var(prep.data_test_index[id(test)])
            if not m.has(name):
                m.declare(name)
                data.append(name)
        elif isinstance(test, ir.PreRef):
            name = pre_bit(prep.pre_signals.index(test.signal))
            if not m.has(name):
                reg(name)
        elif isinstance(test, ir.SigNot):
            tests(test.operand)
        elif isinstance(test, (ir.SigAnd, ir.SigOr)):
            tests(test.left)
            tests(test.right)

    stack = [prep.root]
    while stack:
        node = stack.pop()
        if node.kind == PAUSE:
            reg(register(node.pid))
        elif node.kind in (PRESENT, SUSPEND):
            tests(node.src.test)
        stack.extend(reversed(node.children))
    for k in range(len(prep.pre_signals)):
        if not m.has(pre_bit(k)):
            reg(pre_bit(k))
    for index in range(len(program.inputs)):
        name = input_var(index)
        if not m.has(name):
            m.declare(name)
            inputs.append(name)
    for number in range(len(prep.data_tests)):
        name = data_var(number)
        if not m.has(name):
            m.declare(name)
            data.append(name)
    return registers, inputs, data


def _relations(m: Manager, program: ir.Program) -> Node:
    """Where the inputs satisfy every ``relation`` of the program."""
    result = m.true
    for relation in program.relations:
        bits = [m.var(input_var(program.inputs.index(s))) for s in relation.signals]
        if relation.kind == "#":
            for i, a in enumerate(bits):
                for b in bits[i + 1:]:
                    result &= ~(a & b)
        else:
            result &= ~bits[0] | bits[1]
    return result


def build_circuit(prep: Prepared, manager: Manager | None = None,
                  tracked: tuple[ir.VarDecl, ...] = ()) -> Circuit:
    """The circuit of ``prep``: its walks iterated to the signals' fixpoint; ``tracked``: the
    variables kept exactly (:mod:`.circuit_data`), the other data abstracted."""
    m = manager or Manager()
    registers, inputs, data = _declare(m, prep, tracked)
    circuit = Circuit(prep, m, registers, inputs, data, tracked=tracked)
    circuit.relations = _relations(m, prep.program)
    boot, term = m.var(BOOT), m.var(TERM)
    running = ~term
    env: dict = {}
    while True:
        walk = _Walk(circuit, env)
        surface = boot & running
        depth_act = ~boot & running
        codes = walk.go(prep.root, False, (surface, surface), {})
        _merge(codes, walk.go(prep.root, True, (depth_act, depth_act), {}))
        circuit.walks += 1
        circuit.activation_rounds.append({a.visit: a.sure for a in walk.activations})
        changed = False
        keys = set(walk.can) | set(env) | walk.tested
        new_env = {}
        for key in keys:
            present = walk.must.get(key, m.false)
            absent = ~walk.can.get(key, m.false)
            new_env[key] = (present, absent)
            old = env.get(key)
            if old is None or old[0] != present or old[1] != absent:
                changed = True
        env = new_env
        if not changed:
            break
        if circuit.walks > MAX_FIXPOINT_WALKS:  # pragma: no cover - monotone, bounded by keys
            break
    _outputs(circuit, walk, codes, env)
    return circuit


def _outputs(circuit: Circuit, walk: _Walk, codes: dict[int, Rail], env: dict) -> None:
    m = circuit.manager
    prep = circuit.prep
    program = prep.program
    boot, term = m.var(BOOT), m.var(TERM)
    running = ~term
    code0 = codes.get(0, (m.false, m.false))[0]
    circuit.code0 = code0
    for decl in (*program.outputs, program.failed, program.aborted):
        if decl is not None:
            circuit.emitted[decl] = walk.must.get(decl, m.false)
    for pid in range(len(prep.pauses)):
        circuit.next[register(pid)] = walk.next.get(pid, m.false) & running
    circuit.next[BOOT] = m.false
    circuit.next[TERM] = term | code0
    bad = m.false
    for decl in (program.failed, program.aborted):
        if decl is not None:
            bad |= circuit.emitted[decl]
    circuit.next[FAILED_BEFORE] = m.var(FAILED_BEFORE) | bad
    for k, decl in enumerate(prep.pre_signals):
        name = pre_bit(k)
        if decl.kind == ir.INPUT:
            present = m.var(input_var(program.inputs.index(decl)))
        elif decl.kind == ir.LOCAL:
            fresh = walk.fresh.get(decl, m.false)
            present = ((fresh & walk.must.get((decl, False), m.false))
                       | (~fresh & walk.must.get((decl, True), m.false)))
            suspended = _suspended(circuit, walk, decl)
            present = (suspended & m.var(name)) | (~suspended & present)
        else:
            present = walk.must.get(decl, m.false)
        circuit.next[name] = present & running & ~code0
    circuit.evaluated = walk.evaluated
    for k, var in enumerate(circuit.tracked):
        for bit, value in enumerate(walk.values[var]):
            circuit.next[counter_bit(k, bit)] = value & running & ~code0
    circuit.overflow = walk.arithmetic.overflow
    circuit.relations &= walk.constraints
    circuit.activations = walk.activations
    circuit.undecided = [(where, loc, name) for where, loc, name in walk.undecided
                         if where != m.false]
    del boot


def _suspended(circuit: Circuit, walk: _Walk, decl: ir.SignalDecl) -> Node:
    """Where the declaration of local ``decl`` is alive inside a suspend frozen in the
    instant (its ``pre`` then keeps the value of the last instant its scope ran)."""
    m = circuit.manager
    result = m.false
    for index, lo, hi in circuit.prep.local_nodes.get(decl, ()):
        if lo == hi:
            continue
        alive = circuit.selected(lo, hi)
        for frozen, where in walk.frozen:
            if frozen.index < index and frozen.lo <= lo and hi <= frozen.hi:
                result |= alive & where
    return result
