"""Runtime verdicts of LTL properties on a finite run: true, false or undecided.

A run is a finite word of instants (letters: the atoms true in each reaction, as in
:mod:`.letters`). Its verdict on a property, with the checker's own formula
(:func:`~.formula.from_ast`) and semantics:

- **the mission ended** (``done``, ``failed`` or ``aborted``): after its end a run *stutters*
  (instants with no output, no active task, no status atom: the model's convention, inputs
  taken absent), so the infinite word is ``prefix · ∅^ω`` and the reference semantics
  (:func:`~.lasso.holds_on_lasso`) decides it: ``true`` or ``false``;
- **the run was cut** (``timeout``, a run-time failure, Ctrl-C): the LTL3 verdict (Bauer,
  Leucker, Schallhart, *Runtime verification for LTL and TLTL*, TOSEM 2011): ``false`` when
  no infinite continuation of the prefix satisfies the property, ``true`` when none violates
  it, ``undecided`` otherwise. Decided on the checker's tableau (:mod:`.tableau`): the prefix
  is read from the tableau's initial states; a continuation exists when some state reached can
  reach a strongly connected component whose edges cover every acceptance set, over all
  letters of the property's atoms.
"""

from __future__ import annotations

import functools
from enum import Enum
from itertools import product
from typing import Sequence

import networkx as nx

from orccad_app.verify.formula import F, atoms, neg
from orccad_app.verify.lasso import holds_on_lasso
from orccad_app.verify.tableau import Tableau

__all__ = ["Verdict", "ltl_verdict", "LtlMonitor", "MAX_MONITOR_ATOMS"]

MAX_MONITOR_ATOMS = 12
"""Atoms allowed in a property monitored on a cut run (2^n letters are explored)."""


class Verdict(str, Enum):
    """A property's verdict on one run."""

    TRUE = "true"
    FALSE = "false"
    UNDECIDED = "undecided"


class _Bits:
    """The alphabet the tableau needs: atom key -> bit."""

    def __init__(self, keys) -> None:
        self.keys = sorted(keys)
        self.bit = {key: i for i, key in enumerate(self.keys)}

    def mask(self, letter: frozenset) -> int:
        return sum(1 << self.bit[key] for key in letter if key in self.bit)


def ltl_verdict(formula: F, word: Sequence[frozenset], ended: bool) -> Verdict:
    """The verdict of ``formula`` on ``word`` (letters: sets of atom keys; see the module
    docstring); ``ended``: the mission terminated in the word's last instant."""
    if ended or not word:
        if not word:
            word = [frozenset()]
        holds = holds_on_lasso(formula, list(word), [frozenset()])
        return Verdict.TRUE if holds else Verdict.FALSE
    bits = _Bits(atoms(formula))
    if len(bits.keys) > MAX_MONITOR_ATOMS:
        return Verdict.UNDECIDED
    if not _extensible(formula, bits, word):
        return Verdict.FALSE
    if not _extensible(neg(formula), bits, word):
        return Verdict.TRUE
    return Verdict.UNDECIDED


@functools.lru_cache(maxsize=64)
def _monitor(formula: F, keys: tuple) -> _Monitor:
    """The tableau of ``formula`` over the atoms ``keys`` with its caches, built once per
    process: a campaign's worker judges the same properties on every run, and building a
    tableau generates and compiles its evaluation code."""
    return _Monitor(Tableau(formula, _Bits(keys)))  # type: ignore[arg-type]


class _Monitor:
    """A tableau and what reading words through it has computed: the states reached from a
    set of states by a letter, and the live states of a set (both bounded in size)."""

    LIMIT = 4096

    def __init__(self, tableau: Tableau) -> None:
        self.tableau = tableau
        self.steps: dict[tuple[frozenset, int], frozenset] = {}
        self.live: dict[frozenset, set] = {}

    def step(self, states: frozenset, mask: int) -> frozenset:
        key = (states, mask)
        found = self.steps.get(key)
        if found is None:
            if len(self.steps) >= self.LIMIT:
                self.steps.clear()
            successors = self.tableau.successors
            found = self.steps[key] = frozenset(
                (yn, guess) for prev, required in states
                for guess, yn, _ in successors(mask, prev, required))
        return found

    def extensible(self, states: frozenset, bits: _Bits) -> bool:
        """Some state of ``states`` (reached by a prefix) starts an accepting run."""
        alive = self.live.get(states)
        if alive is None:
            if len(self.live) >= self.LIMIT:  # bounded memory: forget and start again
                self.live.clear()
            alive = self.live[states] = _live_states(self.tableau, bits, set(states))
        return bool(states & alive)


class _Prefix:
    """The tableau states a prefix read so far reaches (``_extensible``, one letter at a
    time), on the formula's shared :class:`_Monitor`."""

    def __init__(self, formula: F, bits: _Bits) -> None:
        self.monitor = _monitor(formula, tuple(bits.keys))
        self.bits = bits
        self.states: frozenset = frozenset({(0, None)})

    def read(self, letters: Sequence[frozenset]) -> None:
        step, bits = self.monitor.step, self.bits
        for letter in letters:
            if not self.states:
                return
            self.states = step(self.states, bits.mask(letter))

    def extensible(self) -> bool:
        return bool(self.states) and self.monitor.extensible(self.states, self.bits)


class LtlMonitor:
    """:func:`ltl_verdict` of one formula on a growing run, each letter read once: the
    verdict of a run's prefix at any time costs the letters new since the last one (the
    live-state search of LTL3 is bounded by the tableau, not by the run); a run that ended is
    judged by :func:`ltl_verdict` (its lasso)."""

    def __init__(self, formula: F) -> None:
        self.formula = formula
        self._bits = _Bits(atoms(formula))
        self._too_large = len(self._bits.keys) > MAX_MONITOR_ATOMS
        self._prefixes = (None if self._too_large else
                          (_Prefix(formula, self._bits), _Prefix(neg(formula), self._bits)))
        self._read = 0

    def verdict(self, word: Sequence[frozenset], ended: bool) -> Verdict:
        """The verdict of the formula on ``word``, which extends every word given before."""
        if ended or not word:
            return ltl_verdict(self.formula, word, ended)
        if self._prefixes is None:
            return Verdict.UNDECIDED
        holds, fails = self._prefixes
        new = word[self._read:]
        self._read = len(word)
        holds.read(new)
        fails.read(new)
        if not holds.extensible():
            return Verdict.FALSE
        if not fails.extensible():
            return Verdict.TRUE
        return Verdict.UNDECIDED


def _extensible(formula: F, bits: _Bits, word: Sequence[frozenset]) -> bool:
    """Some infinite continuation of ``word`` satisfies ``formula``."""
    monitor = _monitor(formula, tuple(bits.keys))
    masks: dict[frozenset, int] = {}
    states: frozenset = frozenset({(0, None)})
    step = monitor.step
    settled = -1  # a mask whose step leaves ``states`` as they are: its repeats are skipped
    for letter in word:
        mask = masks.get(letter)
        if mask is None:
            mask = masks[letter] = bits.mask(letter)
        if mask == settled:
            continue
        following = step(states, mask)
        if not following:
            return False
        settled = mask if following == states else -1
        states = following
    return monitor.extensible(states, bits)


def _live_states(tableau: Tableau, bits: _Bits, start: set) -> set:
    """The states reachable from ``start`` from which an accepting cycle is reachable."""
    letters = [sum(1 << i for i, on in enumerate(choice) if on)
               for choice in product((False, True), repeat=len(bits.keys))]
    graph = nx.DiGraph()
    accept: dict[tuple, int] = {}
    frontier = list(start)
    graph.add_nodes_from(start)
    while frontier:
        state = frontier.pop()
        prev, required = state
        for letter in letters:
            for guess, yn, acc in tableau.successors(letter, prev, required):
                target = (yn, guess)
                edge = (state, target)
                accept[edge] = accept.get(edge, 0) | acc
                if target not in graph:
                    frontier.append(target)
                graph.add_edge(state, target)
    full = (1 << tableau.acceptance_count) - 1
    good: set = set()
    for component in nx.strongly_connected_components(graph):
        covered = 0
        for u in component:
            for v in graph.successors(u):
                if v in component:
                    covered |= accept[(u, v)]
        if covered == full and any(v in component for u in component
                                   for v in graph.successors(u)):
            good |= component
    if not good:
        return set()
    reverse = graph.reverse(copy=False)
    live = set(good)
    for node in good:
        live |= nx.descendants(reverse, node)
    return live
