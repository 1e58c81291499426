"""Preparation of kernel IR for the engine: numbering and static checks.

:func:`prepare` turns an :class:`~orccad_app.reactive.ir.Program` into a tree of
:class:`KNode` objects where

- every ``pause`` has a number, in depth-first order, so every statement owns the contiguous
  interval ``[lo, hi)`` of the pauses inside it: a control state (a set of active pauses) is
  "inside" a statement when one of its pauses falls in that interval;
- every trap has a completion code: 0 terminated, 1 paused, and ``2 + k`` for an exit of the
  trap nested ``k`` levels *inside* the outermost one… reversed, so that outer traps have the
  larger code and win in ``max`` (Esterel's completion codes);
- every data test has a number (the decision it stands for in the automaton).

It also rejects instantaneous loops: a loop whose body can terminate in the instant it starts
(all tests taken both ways) is a compile error at the loop's location.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from orccad_app.diagnostics import OrccadError
from orccad_app.reactive import ir

__all__ = [
    "KNode", "Prepared", "prepare",
    "NOTHING", "PAUSE", "EMIT", "PRESENT", "SEQ", "LOOP", "PAR", "TRAP", "EXIT", "SUSPEND",
    "LOCAL", "ASSIGN", "MARK", "TERMINATED", "PAUSED",
]

(NOTHING, PAUSE, EMIT, PRESENT, SEQ, LOOP, PAR, TRAP, EXIT, SUSPEND, LOCAL, ASSIGN,
 MARK) = range(13)
TERMINATED, PAUSED = 0, 1

_KIND = {
    ir.Nothing: NOTHING, ir.Pause: PAUSE, ir.Emit: EMIT, ir.Present: PRESENT, ir.Seq: SEQ,
    ir.Loop: LOOP, ir.Par: PAR, ir.Trap: TRAP, ir.Exit: EXIT, ir.Suspend: SUSPEND,
    ir.Local: LOCAL, ir.Assign: ASSIGN, ir.Mark: MARK,
}


class KNode:
    """A kernel statement ready for the engine (mutable only while being prepared)."""

    __slots__ = ("kind", "src", "children", "lo", "hi", "code", "pid", "child_los", "index",
                 "in_loop")

    def __init__(self, kind: int, src: ir.Stmt, index: int):
        self.kind = kind
        self.src = src
        self.index = index
        self.children: tuple[KNode, ...] = ()
        self.lo = self.hi = 0
        self.code = 0          # exit code of a trap (TRAP) or of its exit (EXIT)
        self.pid = -1          # pause number (PAUSE)
        self.child_los: tuple[int, ...] = ()  # SEQ: lo of each child, for bisection
        self.in_loop = False   # inside a loop body (a LOCAL there has several incarnations)

    def __repr__(self) -> str:  # pragma: no cover - debugging aid
        return f"KNode({type(self.src).__name__}@{self.src.loc}, [{self.lo},{self.hi}))"


@dataclass
class Prepared:
    """The prepared program: root node, pause table and data-test table."""

    program: ir.Program
    root: KNode
    pauses: list[KNode] = field(default_factory=list)
    data_tests: list[ir.DataTest] = field(default_factory=list)
    data_test_index: dict[int, int] = field(default_factory=dict)  # id(DataTest) -> number
    marks: list[tuple[tuple, int, int]] = field(default_factory=list)  # (label, lo, hi)
    nodes: int = 0
    #: signals with a valued emission somewhere: reading ?S of another signal never waits
    valued_emitted: set = field(default_factory=set)
    #: signals whose ``pre(S)`` is tested; the control state holds, after the pauses, one
    #: number ``pre_base + k`` for each ``pre_signals[k]`` present in the previous instant
    pre_signals: list = field(default_factory=list)
    pre_base: int = 0
    #: each local signal's declaration nodes (``signal S { … }``): (node index, lo, hi) —
    #: ``pre(S)`` of a local skips the instants its declaration is suspended
    local_nodes: dict = field(default_factory=dict)
    #: expressions made by the engine (combinations, faults), made once so that equal events
    #: of two runs are the same objects
    made: dict = field(default_factory=dict)
    #: a valued signal without ``combine`` emitted twice in a reaction is a run-time error of
    #: that reaction (an ``ir.Fault``) even where no data test could rule it out: how a run
    #: sees it (``orccad react``, the generated C), not how ``check`` judges the program
    defer_double_emissions: bool = False


def _children(stmt: ir.Stmt) -> tuple[ir.Stmt, ...]:
    if isinstance(stmt, ir.Seq):
        return stmt.items
    if isinstance(stmt, ir.Par):
        return stmt.branches
    if isinstance(stmt, ir.Present):
        return (stmt.then, stmt.orelse)
    if isinstance(stmt, (ir.Loop, ir.Trap, ir.Suspend, ir.Local, ir.Mark)):
        return (stmt.body,)
    return ()


def _tests_of(test: ir.Test):
    if isinstance(test, (ir.DataTest, ir.PreRef)):
        yield test
    elif isinstance(test, ir.SigNot):
        yield from _tests_of(test.operand)
    elif isinstance(test, (ir.SigAnd, ir.SigOr)):
        yield from _tests_of(test.left)
        yield from _tests_of(test.right)


class _Builder:
    def __init__(self, program: ir.Program):
        self.out = Prepared(program, root=None)  # type: ignore[arg-type]
        self.trap_level: dict[ir.TrapDecl, int] = {}
        self.max_level = 0

    def build(self, stmt: ir.Stmt, level: int, in_loop: bool = False) -> KNode:
        node = KNode(_KIND[type(stmt)], stmt, self.out.nodes)
        node.in_loop = in_loop
        self.out.nodes += 1
        node.lo = len(self.out.pauses)
        if node.kind == PAUSE:
            node.pid = len(self.out.pauses)
            self.out.pauses.append(node)
        elif node.kind == TRAP:
            self.trap_level[stmt.trap] = level
            self.max_level = max(self.max_level, level + 1)
        elif node.kind == EXIT and stmt.trap not in self.trap_level:
            raise OrccadError(f"'exit {stmt.trap.name}' is outside the trap it names", stmt.loc)
        elif node.kind == PRESENT or node.kind == SUSPEND:
            for test in _tests_of(stmt.test):  # derived forms may share one test object
                if isinstance(test, ir.PreRef):
                    if test.signal not in self.out.pre_signals:
                        self.out.pre_signals.append(test.signal)
                elif id(test) not in self.out.data_test_index:
                    self.out.data_test_index[id(test)] = len(self.out.data_tests)
                    self.out.data_tests.append(test)
        elif node.kind == EMIT and stmt.value is not None:
            self.out.valued_emitted.add(stmt.signal)
        inner = level + 1 if node.kind == TRAP else level
        looped = in_loop or node.kind == LOOP
        node.children = tuple(self.build(child, inner, looped) for child in _children(stmt))
        if node.kind == LOCAL:
            for decl in stmt.signals:
                self.out.local_nodes.setdefault(decl, []).append(
                    (node.index, node.lo, len(self.out.pauses)))
        if node.kind == TRAP:
            del self.trap_level[stmt.trap]
        node.hi = len(self.out.pauses)
        if node.kind == SEQ:
            node.child_los = tuple(child.lo for child in node.children)
        elif node.kind == MARK and node.hi > node.lo:
            self.out.marks.append((stmt.label, node.lo, node.hi))
        if node.kind == EXIT:
            node.code = self.trap_level[stmt.trap]  # level for now; made a code below
        elif node.kind == TRAP:
            node.code = level
        return node


def _assign_codes(node: KNode, max_level: int) -> None:
    stack = [node]
    while stack:
        n = stack.pop()
        if n.kind in (TRAP, EXIT):
            n.code = 2 + (max_level - 1 - n.code)
        stack.extend(n.children)


def max_combine(left: int, right: int) -> int:
    """Completion-code sets as bitmasks: the set ``{max(a, b) | a ∈ left, b ∈ right}``."""
    result = 0
    a_bits = [k for k in range(left.bit_length()) if left >> k & 1]
    b_bits = [k for k in range(right.bit_length()) if right >> k & 1]
    for a in a_bits:
        for b in b_bits:
            result |= 1 << max(a, b)
    return result


def surface_codes(node: KNode, memo: dict[int, int]) -> int:
    """Completion codes the statement can return in its first instant, tests both ways."""
    cached = memo.get(node.index)
    if cached is not None:
        return cached
    kind = node.kind
    if kind in (NOTHING, EMIT, ASSIGN):
        codes = 1 << TERMINATED
    elif kind == PAUSE:
        codes = 1 << PAUSED
    elif kind == EXIT:
        codes = 1 << node.code
    elif kind == PRESENT:
        codes = surface_codes(node.children[0], memo) | surface_codes(node.children[1], memo)
    elif kind == SEQ:
        codes = 1
        for child in node.children:
            child_codes = surface_codes(child, memo)
            codes = (codes & ~1) | child_codes
            if not child_codes & 1:
                break
    elif kind == PAR:
        codes = 1
        for child in node.children:
            codes = max_combine(codes, surface_codes(child, memo))
    elif kind == TRAP:
        codes = surface_codes(node.children[0], memo)
        if codes >> node.code & 1:
            codes = (codes & ~(1 << node.code)) | 1
    else:  # LOOP, SUSPEND, LOCAL, MARK
        codes = surface_codes(node.children[0], memo)
    memo[node.index] = codes
    return codes


def _check_loops(root: KNode) -> None:
    memo: dict[int, int] = {}
    order: list[KNode] = []
    stack = [root]
    while stack:
        n = stack.pop()
        order.append(n)
        stack.extend(n.children)
    for n in reversed(order):  # innermost loops first
        if n.kind == LOOP and surface_codes(n.children[0], memo) & 1:
            what = n.src.what
            raise OrccadError(
                f"instantaneous loop: the body of this {what} can terminate in the instant "
                "it starts (add a 'pause' or an 'await' on every path)", n.src.loc)


def prepare(program: ir.Program) -> Prepared:
    """Number pauses, traps and data tests of ``program``; reject instantaneous loops."""
    builder = _Builder(program)
    root = builder.build(program.body, 0)
    _assign_codes(root, builder.max_level)
    builder.out.root = root
    builder.out.pre_base = len(builder.out.pauses)
    _check_loops(root)
    return builder.out
