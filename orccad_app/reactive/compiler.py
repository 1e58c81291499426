"""Compilation of a reactive program to an explicit automaton.

Starting from the boot state, each reachable control state is reacted *symbolically*: the
engine (:mod:`.engine`) asks an oracle for input presences and data-test outcomes as it needs
them, and the compiler answers every way, building the state's reaction tree:

1. input tests first — when the engine asks for an input not yet decided on this path, the
   tree branches on it (present, then absent), so only the inputs a state actually looks at
   are tested, in the order it looks at them;
2. then, for one full input valuation, every combination of data-test outcomes is explored
   depth-first; the recorded run-time events of each run (assignments, valued emissions, data
   tests in execution order) are merged into a trie that becomes the data part of the tree.

New control states found at the leaves are explored in turn (breadth first), up to a state
budget; the result is minimized by bisimulation (:mod:`.minimize`).
"""

from __future__ import annotations

from collections import deque
from typing import Callable

from orccad_app.diagnostics import OrccadError
from orccad_app.reactive import ir
from orccad_app.reactive.automaton import TERMINAL, Action, Automaton, DataBranch, InputTest, Leaf
from orccad_app.reactive.status import Status
from orccad_app.reactive.engine import BOOT, Outcome, react
from orccad_app.reactive.minimize import minimize
from orccad_app.reactive.prepare import TERMINATED, Prepared, prepare

__all__ = ["compile_program", "DEFAULT_MAX_STATES", "TERMINAL", "state_budget_error",
           "StateBudgetExceeded", "TransitionBudgetExceeded"]

class StateBudgetExceeded(OrccadError):
    """The program has more reachable states (or transitions of one state) than the budget."""


class TransitionBudgetExceeded(StateBudgetExceeded):
    """The explicit automaton would have more transitions than the caller allows (a caller
    with another way, such as the symbolic checker, stops the tabulation early)."""


#: Default state budget; ``orccad compile --max-states`` changes it.
DEFAULT_MAX_STATES = 20_000
#: Reaction-tree leaves allowed per state before the compiler gives up.
MAX_LEAVES_PER_STATE = 200_000


class _Oracle:
    """Answers inputs from a valuation and data tests from a depth-first prefix.

    An input not in the valuation (nor forced by a relation) is answered *present* and noted
    in ``new``: the run is then the one of the valuation extended with those inputs present,
    and the compiler branches on them without running it again (:meth:`_Explorer._branch`).
    """

    __slots__ = ("valuation", "prefix", "asked", "answers", "relations", "new")

    def __init__(self, valuation: dict, prefix: list[bool], relations=()):
        self.valuation = valuation
        self.prefix = prefix
        self.asked: dict[int, bool] = {}
        self.answers: list[bool] = []
        self.relations = relations
        self.new: list[ir.SignalDecl] = []

    def input(self, signal: ir.SignalDecl) -> bool:
        try:
            return self.valuation[signal]
        except KeyError:
            forced = _forced(signal, self.valuation, self.relations)
            if forced is not None:
                return forced
            if not self.new:
                self.valuation = dict(self.valuation)
            self.new.append(signal)
            self.valuation[signal] = True
            return True

    def data(self, number: int) -> bool:
        answer = self.asked.get(number)
        if answer is None:
            position = len(self.answers)
            answer = self.prefix[position] if position < len(self.prefix) else True
            self.asked[number] = answer
            self.answers.append(answer)
        return answer


def _next_prefix(answers: list[bool]) -> list[bool] | None:
    """The data-test prefix of the next depth-first run after one that gave ``answers``
    (``None`` when every combination was run)."""
    prefix = list(answers)
    while prefix and prefix[-1] is False:
        prefix.pop()
    if not prefix:
        return None
    prefix[-1] = False
    return prefix


def _forced(signal: ir.SignalDecl, valuation: dict, relations) -> bool | None:
    """The status of input ``signal`` the relations impose given ``valuation``, if any: the
    transitions that would violate a relation are never built."""
    for relation in relations:
        if signal not in relation.signals:
            continue
        if relation.kind == "#":
            if any(valuation.get(other) for other in relation.signals if other is not signal):
                return False
        else:
            left, right = relation.signals
            if signal is right and valuation.get(left) is True:
                return True
            if signal is left and valuation.get(right) is False:
                return False
    return None

class _Explorer:
    def __init__(self, prep: Prepared, max_states: int, max_leaves: int | None = None):
        self.prep = prep
        self.max_states = max_states
        self.leaves = 0
        self.total = 0
        self.max_leaves = max_leaves

    def tree(self, state) -> object:
        self.leaves = 0
        if state == TERMINAL:
            return Leaf(TERMINAL, (), Status.DONE)
        return self._inputs(state, {})

    def _inputs(self, state, valuation: dict, runs: list[Outcome] | None = None,
                prefix: list[bool] | None = None):
        """The tree of ``state`` under input ``valuation``, going on from ``runs`` (the data
        combinations run so far, which asked no input outside the valuation) at ``prefix``."""
        runs = [] if runs is None else runs
        next_prefix: list[bool] | None = [] if prefix is None else prefix
        while next_prefix is not None:
            oracle = _Oracle(valuation, next_prefix, self.prep.program.relations)
            outcome = react(self.prep, state, oracle)
            self._count(1)
            if oracle.new:
                return self._branch(state, valuation, runs, next_prefix, outcome, oracle, 0)
            runs.append(outcome)
            next_prefix = _next_prefix(oracle.answers)
        return self._trie(runs, 0)

    def _branch(self, state, valuation: dict, runs: list[Outcome], prefix: list[bool],
                outcome: Outcome, oracle: _Oracle, depth: int):
        """Branch on the ``depth``-th input ``outcome`` asked first: ``outcome`` is a run of
        the then-branch; the else-branch runs the same data combination again."""
        signal = oracle.new[depth]
        saved = list(runs)
        on = {**valuation, signal: True}
        if depth + 1 < len(oracle.new):
            then = self._branch(state, on, runs, prefix, outcome, oracle, depth + 1)
        else:
            runs.append(outcome)
            following = _next_prefix(oracle.answers)
            then = (self._trie(runs, 0) if following is None
                    else self._inputs(state, on, runs, following))
        self._count(len(saved))  # the runs before hold in the else-branch too
        orelse = self._inputs(state, {**valuation, signal: False}, saved, prefix)
        return then if then == orelse else InputTest(signal, then, orelse)

    def _count(self, leaves: int) -> None:
        self.leaves += leaves
        self.total += leaves
        if self.max_leaves is not None and self.total > self.max_leaves:
            raise TransitionBudgetExceeded(
                f"'{self.prep.program.name}' has more than {self.max_leaves} transitions",
                self.prep.program.loc)
        if self.leaves > MAX_LEAVES_PER_STATE:
            raise StateBudgetExceeded(
                f"state explosion: one state of '{self.prep.program.name}' needs more than "
                f"{MAX_LEAVES_PER_STATE} transitions", self.prep.program.loc)

    def _trie(self, runs: list[Outcome], pos: int):
        first = runs[0]
        if pos == len(first.events):
            leaf = self._leaf(first)
            if any(len(r.events) != pos or self._leaf(r) != leaf for r in runs[1:]):
                raise self._ambiguous(None)
            return leaf
        event = first.events[pos]
        if any(len(r.events) <= pos for r in runs):
            raise self._ambiguous(event)
        if event[0] == "test":
            number = event[1]
            if any(r.events[pos][:2] != ("test", number) for r in runs):
                raise self._ambiguous(event)
            yes = [r for r in runs if r.events[pos][2]]
            no = [r for r in runs if not r.events[pos][2]]
            if not yes or not no:
                raise self._ambiguous(event)
            then, orelse = self._trie(yes, pos + 1), self._trie(no, pos + 1)
            return then if then == orelse else DataBranch(number, then, orelse)
        if any(r.events[pos] != event for r in runs):
            raise self._ambiguous(event)
        return Action(event[0], event[1], event[2], self._trie(runs, pos + 1))

    def _leaf(self, outcome: Outcome) -> Leaf:
        program = self.prep.program
        emitted = tuple(s for s in program.outputs if s in outcome.emitted)
        target = TERMINAL if outcome.code == TERMINATED else outcome.state
        if program.aborted is not None and program.aborted in outcome.emitted:
            status = Status.ABORTED
        elif program.failed is not None and program.failed in outcome.emitted:
            status = Status.FAILED
        else:
            status = Status.DONE if outcome.code == TERMINATED else Status.RUNNING
        return Leaf(target, emitted, status)

    def _ambiguous(self, event) -> OrccadError:
        loc = self.prep.program.loc
        if event is not None and event[0] == "test":
            loc = self.prep.data_tests[event[1]].loc
        elif event is not None:
            loc = getattr(event[2], "loc", loc)
        return OrccadError(
            "non-causal program: a data condition decides the status of a signal that is "
            "used earlier in the same instant (test the data first, in a branch of its own)", loc)


def compile_program(program: ir.Program, *, max_states: int = DEFAULT_MAX_STATES,
                    progress: Callable[[int], None] | None = None,
                    max_transitions: int | None = None,
                    defer_double_emissions: bool = False) -> Automaton:
    """Compile ``program`` to a minimized deterministic automaton.

    Raises :class:`OrccadError` (with a location) for instantaneous loops, non-causal programs
    and when more than ``max_states`` control states are reachable. ``progress`` is called
    with the number of control states explored after each one. ``defer_double_emissions``:
    a valued signal without ``combine`` emitted twice in a transition makes that transition
    raise when it is taken (what ``orccad react`` does, and the generated C) instead of
    refusing the program (what ``orccad check`` does).
    """
    prep = prepare(program)
    prep.defer_double_emissions = defer_double_emissions
    explorer = _Explorer(prep, max_states, max_transitions)
    trees: dict[object, object] = {}
    queue: deque = deque([BOOT])
    seen = {BOOT}
    while queue:
        state = queue.popleft()
        tree = explorer.tree(state)
        trees[state] = tree
        if progress is not None:
            progress(len(trees))
        for target in _targets(tree):
            if target not in seen:
                if len(seen) >= max_states:
                    raise state_budget_error(program, max_states)
                seen.add(target)
                queue.append(target)
    waiting = {key: _waiting(prep, key) for key in trees}
    by_pause = _labels_by_pause(prep)
    labels = {key: _labels(by_pause, key) for key in trees}
    return minimize(program, trees, BOOT, waiting, labels, prep.data_tests, _variables(prep))


def state_budget_error(program: ir.Program, max_states: int) -> StateBudgetExceeded:
    """The located error of a program with more than ``max_states`` reachable states."""
    return StateBudgetExceeded(f"state budget exceeded: '{program.name}' has more than {max_states} "
                       "reachable control states (raise the budget with --max-states)",
                       program.loc)


def _targets(tree):
    stack = [tree]
    while stack:
        node = stack.pop()
        if isinstance(node, Leaf):
            yield node.target
        elif isinstance(node, Action):
            stack.append(node.next)
        else:
            stack.append(node.orelse)
            stack.append(node.then)


def _waiting(prep: Prepared, key) -> tuple:
    if key is BOOT or key == TERMINAL:
        return ()
    return tuple(prep.pauses[pid].src.loc for pid in key if pid < prep.pre_base)


def _labels_by_pause(prep: Prepared) -> list[frozenset]:
    """For each pause, the labels of the marked regions around it."""
    around: list[set] = [set() for _ in prep.pauses]
    for label, lo, hi in prep.marks:
        for pause in range(lo, hi):
            around[pause].add(label)
    return [frozenset(labels) for labels in around]


def _labels(by_pause: list[frozenset], key) -> frozenset:
    """Labels of the marked regions holding an active pause of control state ``key``."""
    if key is BOOT or key == TERMINAL:
        return frozenset()
    return frozenset().union(*(by_pause[p] for p in key if p < len(by_pause)))


def _variables(prep: Prepared) -> tuple[ir.VarDecl, ...]:
    found: dict[ir.VarDecl, None] = {}
    stack = [prep.root]
    while stack:
        node = stack.pop()
        if isinstance(node.src, ir.Assign):
            found.setdefault(node.src.var)
        stack.extend(reversed(node.children))
    return tuple(found)
