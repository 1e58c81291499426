"""An automaton built on demand, for running: the states and transitions an execution takes.

``orccad compile`` and ``orccad check`` build every reachable state (:mod:`.compiler`); a run
needs only the states it visits — a mission of 12 parallel branches has 4 097 states and
531 442 transitions, a run a handful. :class:`LazyAutomaton` builds, at the first instant that
needs it, the one path of a state's reaction tree that the instant's inputs select:

- the control state is reacted by the same constructive engine as the full compile, its inputs
  answered from the instant's inputs (recording which the engine looked at, in the order it
  looked: the input tests of the full tree, on that path) and its data tests explored every
  way (the data part of the tree, :meth:`.compiler._Explorer._trie`, whole);
- the path is added to the state's lowered tree (:mod:`.lowered`), shared by every reactor of
  the automaton (a campaign's runs reuse what earlier runs built);
- a control state reached for the first time gets the next state number: numbers are given in
  order of discovery, so they depend on the inputs seen, but a state's labels and waiting
  points are those of its control state, as in the full automaton.

The decision trees are those of the full compile before minimization (the full automaton
merges bisimilar states and drops an input test whose two branches are equal: the lazy tree
keeps them, with the same outcome either way). The budgets are the full compile's: at most
``max_states`` states and :data:`~.compiler.MAX_LEAVES_PER_STATE` transitions per state, and
the compile errors (non-causal programs, run-time faults found statically) are the same,
located, raised at the first instant that reaches them — as HipHop, which also runs Esterel
programs without compiling them whole, reports causality errors when it meets them.
"""

from __future__ import annotations

from typing import Container, Iterator

from orccad_app.reactive import ir
from orccad_app.reactive.automaton import TERMINAL, Action, DataBranch, InputTest, Leaf, Node
from orccad_app.reactive.status import Status
from orccad_app.reactive.compiler import (DEFAULT_MAX_STATES, MAX_LEAVES_PER_STATE,
                                          StateBudgetExceeded, _Explorer,
                                          _forced, _labels, _labels_by_pause, _variables,
                                          _waiting, state_budget_error)
from orccad_app.reactive.engine import BOOT, Outcome, react
from orccad_app.reactive.lowered import INPUT, lower
from orccad_app.reactive.prepare import ASSIGN, EMIT, prepare

__all__ = ["LazyAutomaton"]


class _InstantOracle:
    """Answers inputs from one instant's inputs (recording the ones asked, in order) and data
    tests from a depth-first prefix, like the compiler's oracle."""

    __slots__ = ("present", "asked", "order", "prefix", "data_asked", "answers", "relations")

    def __init__(self, present: Container[str], asked: dict, order: list, prefix: list[bool],
                 relations) -> None:
        self.present = present
        self.asked = asked          # input -> presence, shared by the runs of one instant
        self.order = order          # (input, presence) in the order first asked
        self.prefix = prefix
        self.data_asked: dict[int, bool] = {}
        self.answers: list[bool] = []
        self.relations = relations

    def input(self, signal: ir.SignalDecl) -> bool:
        answer = self.asked.get(signal)
        if answer is not None:
            return answer
        forced = _forced(signal, self.asked, self.relations)
        if forced is not None:
            return forced
        answer = signal.name in self.present
        self.asked[signal] = answer
        self.order.append((signal, answer))
        return answer

    def data(self, number: int) -> bool:
        answer = self.data_asked.get(number)
        if answer is None:
            position = len(self.answers)
            answer = self.prefix[position] if position < len(self.prefix) else True
            self.data_asked[number] = answer
            self.answers.append(answer)
        return answer


class LazyAutomaton:
    """The automaton of ``program``, built as executions need it (see the module docstring).

    It reads like :class:`~orccad_app.reactive.automaton.Automaton` for what a run needs:
    ``program``, ``name``, ``inputs``, ``outputs``, ``initial``, ``terminal``, and ``labels``
    and ``waiting`` indexed by state number (the states discovered so far).
    """

    def __init__(self, program: ir.Program, *, max_states: int = DEFAULT_MAX_STATES) -> None:
        self.program = program
        self.max_states = max_states
        self.prep = prepare(program)
        self.prep.defer_double_emissions = True  # a run: the instant that makes it fails
        self._explorer = _Explorer(self.prep, max_states)
        self._by_pause = _labels_by_pause(self.prep)
        self.data_tests: tuple[ir.DataTest, ...] = tuple(self.prep.data_tests)
        self.variables: tuple[ir.VarDecl, ...] = _variables(self.prep)
        self.keys: list = []                 # state number -> control-state key
        self._number: dict = {}              # control-state key -> state number
        self._leaves: list[int] = []         # transitions built so far, per state
        self.labels: list[frozenset] = []
        self.waiting: list[tuple] = []
        #: state number -> its lowered reaction tree (``None`` until first reacted)
        self.roots: list = []
        self.initial = self._state(BOOT)

    # ------------------------------------------------------------------ what a run reads
    @property
    def name(self) -> str:
        return self.program.name

    @property
    def inputs(self) -> tuple[ir.SignalDecl, ...]:
        return self.program.inputs

    @property
    def outputs(self) -> tuple[ir.SignalDecl, ...]:
        return self.program.outputs

    @property
    def terminal(self) -> int | None:
        """The number of the terminated program's state, once some run has reached it."""
        return self._number.get(TERMINAL)

    @property
    def state_count(self) -> int:
        """States discovered so far."""
        return len(self.keys)

    def expressions(self) -> Iterator[ir.Expr]:
        """Every expression a reaction may evaluate (data tests, assignments, emissions)."""
        yield from (test.expr for test in self.data_tests)
        stack = [self.prep.root]
        while stack:
            node = stack.pop()
            if node.kind == ASSIGN:
                yield node.src.expr
            elif node.kind == EMIT and node.src.value is not None:
                yield node.src.value
            stack.extend(node.children)

    # ------------------------------------------------------------------ building
    def _state(self, key) -> int:
        number = self._number.get(key)
        if number is None:
            if len(self.keys) >= self.max_states:
                raise state_budget_error(self.program, self.max_states)
            number = self._number[key] = len(self.keys)
            self.keys.append(key)
            self._leaves.append(0)
            self.labels.append(_labels(self._by_pause, key))
            self.waiting.append(_waiting(self.prep, key))
            self.roots.append(None)
        return number

    def expand(self, state: int, inputs: Container[str]) -> tuple:
        """Build the path of state ``state``'s tree that ``inputs`` select (if not built yet);
        returns the state's lowered tree."""
        order, tree = self._explore(state, inputs)
        if len(self.data_tests) != len(self.prep.data_tests):  # a fresh pre(?S) test made
            self.data_tests = tuple(self.prep.data_tests)
        lowered = lower(self._numbered(tree), self.data_tests)
        if not order:
            self.roots[state] = lowered
            return lowered
        if self.roots[state] is None:
            self.roots[state] = [INPUT, order[0][0].name, None, None]
        node = self.roots[state]
        for depth, (signal, present) in enumerate(order):
            assert node[1] == signal.name, "lazy tree: the engine asked inputs in another order"
            branch = 2 if present else 3
            if node[branch] is None:
                node[branch] = (lowered if depth + 1 == len(order)
                                else [INPUT, order[depth + 1][0].name, None, None])
            node = node[branch]
        return self.roots[state]

    def _explore(self, state: int, inputs: Container[str]) -> tuple[list, Node]:
        """The inputs the reaction of ``state`` looks at (in order, with their presence in
        ``inputs``) and the data part of its tree for them (leaf targets: control keys)."""
        key = self.keys[state]
        if key == TERMINAL:
            return [], Leaf(TERMINAL, (), Status.DONE)
        prep, explorer = self.prep, self._explorer
        asked: dict = {}
        order: list = []
        runs: list[Outcome] = []
        prefix: list[bool] = []
        while True:
            oracle = _InstantOracle(inputs, asked, order, prefix, prep.program.relations)
            runs.append(react(prep, key, oracle))
            self._leaves[state] += 1
            if self._leaves[state] > MAX_LEAVES_PER_STATE:
                raise StateBudgetExceeded(
                    f"state explosion: one state of '{prep.program.name}' needs more than "
                    f"{MAX_LEAVES_PER_STATE} transitions", prep.program.loc)
            prefix = oracle.answers
            while prefix and prefix[-1] is False:
                prefix.pop()
            if not prefix:
                break
            prefix[-1] = False
        return order, explorer._trie(runs, 0)

    def _numbered(self, node: Node) -> Node:
        """``node`` with control keys replaced by state numbers (new states numbered)."""
        if isinstance(node, Leaf):
            return Leaf(self._state(node.target), node.emitted, node.status)
        if isinstance(node, DataBranch):
            return DataBranch(node.number, self._numbered(node.then),
                              self._numbered(node.orelse))
        if isinstance(node, InputTest):  # pragma: no cover - the data part tests no input
            return InputTest(node.signal, self._numbered(node.then), self._numbered(node.orelse))
        assert isinstance(node, Action)
        return Action(node.kind, node.target, node.expr, self._numbered(node.next))
