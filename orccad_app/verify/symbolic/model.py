"""The symbolic model: a mission's circuit as a transition relation, its reachable states,
and what the atoms and fairness sets of the explicit model (:mod:`orccad_app.verify.model`)
read, as BDDs.

A state is a valuation of the circuit's registers (``boot``, ``term``, ``failed_before``, the
pauses, the ``pre`` bits); a step is one instant: the registers, the inputs and the outcomes
of the data tests (free: every data value is abstracted) give the next registers. After the
end (``term``) the model stutters, as the explicit one does: no output, no active task, no
status, the inputs free.

Image: the relation is kept as one conjunct ``r' <-> f_r`` per register and the current
variables are quantified as soon as no later conjunct reads them (early quantification);
pre-image: the next-state functions substituted into the set (vector composition).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

from orccad_app.diagnostics import OrccadError, SourceLocation
from orccad_app.reactive import ir
from orccad_app.robottask.composition import Composition
from orccad_app.robottask.labels import RtLabel
from orccad_app.verify import data
from orccad_app.reactive.bdd import Node
from orccad_app.reactive.circuit import (BOOT, FAILED_BEFORE, TERM, Circuit, input_var,
                                                next_name)
from orccad_app.reactive.status import Status

__all__ = ["SymbolicModel", "SymbolicBudgetExceeded", "MAX_IMAGES", "MAX_BDD_NODES"]

#: Breadth-first images allowed for the reachable states (the mission's longest shortest run).
MAX_IMAGES = 100_000
#: BDD nodes the symbolic checker may hold (about 100 bytes each in CUDD: ~1.5 GB).
MAX_BDD_NODES = 15_000_000
#: Breadth-first images allowed with exact counters (a counter that counts every instant
#: would take 2^15 of them): past them the counters are abstracted.
MAX_COUNTER_IMAGES = 1_000
#: Seconds between two counts of the BDD nodes (the budget's check).
BUDGET_EVERY_S = 0.5


class SymbolicBudgetExceeded(OrccadError):
    """The symbolic exploration went over its budget."""


@dataclass
class SymbolicModel:
    """The model of a composition, symbolically (see the module docstring)."""

    composition: Composition
    circuit: Circuit
    reachable: Node = None
    rings: list[Node] = field(default_factory=list)
    fairness: list[str] = field(default_factory=list)
    fair_sets: list[Node] = field(default_factory=list)
    site_active: dict[int, Node] = field(default_factory=dict)
    site_active_next: dict[int, Node] = field(default_factory=dict)

    def __post_init__(self) -> None:
        c = self.circuit
        m = c.manager
        self.m = m
        self.cur = list(c.registers)
        self.nxt = [next_name(r) for r in c.registers]
        self.free = list(c.inputs) + list(c.data)
        self.to_cur = dict(zip(self.nxt, self.cur))
        self.to_next = dict(zip(self.cur, self.nxt))
        self._budget_checked = float("-inf")
        self.term = m.var(TERM)
        self.running = ~self.term
        self.init = m.cube({r: r == BOOT for r in c.registers})
        self.functions = {r: c.next[r] for r in c.registers}
        self._schedule()
        self._sites()
        self._fairness_sets()

    # ------------------------------------------------------------------ relation
    def _schedule(self) -> None:
        """Conjuncts in order, and after each the variables no later conjunct reads."""
        m = self.m
        parts = [(m.var(next_name(r)).equiv(f)) for r, f in self.functions.items()]
        parts.insert(0, self.circuit.relations)
        supports = [m.support(p) for p in parts]
        quantify = set(self.cur) | set(self.free)
        last: dict[str, int] = {}
        for index, support in enumerate(supports):
            for name in support & quantify:
                last[name] = index
        self.parts = parts
        self.after: list[list[str]] = [[] for _ in parts]
        for name, index in last.items():
            self.after[index].append(name)
        self.never_read = [n for n in quantify if n not in last]

    def image(self, states: Node) -> Node:
        """The states one step after ``states``."""
        m = self.m
        result = m.exists(self.never_read, states)
        for part, names in zip(self.parts, self.after):
            result = result & part
            if names:
                result = m.exists(names, result)
        return m.rename(result, self.to_cur)

    def compose(self, states: Node) -> Node:
        """``states`` one instant later, as a function of the current registers, inputs and
        data tests (each register it reads replaced by its next-state function)."""
        support = self.m.support(states)
        functions = {r: f for r, f in self.functions.items() if r in support}
        return self.m.bdd.let(functions, states) if functions else states

    def preimage(self, states: Node) -> Node:
        """The states with a step into ``states``."""
        return self.m.exists(self.free, self.compose(states) & self.circuit.relations)

    def step_relation(self, source: Node, target: Node) -> Node:
        """The steps (current registers, inputs, data tests) from ``source`` into
        ``target`` (``target`` over the current registers)."""
        return source & self.compose(target) & self.circuit.relations

    # ------------------------------------------------------------------ reachability
    def explore(self, max_images: int = MAX_IMAGES) -> Node:
        """The reachable states, breadth first (the rings are kept for shortest runs)."""
        m = self.m
        reached = self.init
        frontier = self.init
        self.rings = [self.init]
        while frontier != m.false:
            if len(self.rings) > max_images:
                raise SymbolicBudgetExceeded(
                    f"mission {self.composition.name}: more than {max_images} instants to "
                    "reach every state", self.composition.mission.loc)
            new = self.image(frontier) & ~reached
            self.check_budget()
            if new == m.false:
                break
            reached = reached | new
            self.rings.append(new)
            frontier = new
        self.reachable = reached
        return reached

    def check_budget(self) -> None:
        """Refuse the mission, located, once the BDDs hold more than :data:`MAX_BDD_NODES`
        nodes, naming the parallel branches that multiply the states. Counting the nodes costs
        a pass over CUDD's tables: it is done at most every :data:`BUDGET_EVERY_S`."""
        now = time.monotonic()
        if now - self._budget_checked < BUDGET_EVERY_S:
            return
        self._budget_checked = now
        if len(self.m.bdd) <= MAX_BDD_NODES:
            return
        composition = self.composition
        raise SymbolicBudgetExceeded(
            f"mission {composition.name} is beyond what can be proved here: its symbolic model "
            f"needs more than {MAX_BDD_NODES} BDD nodes; {widest_par(self.circuit)}",
            composition.mission.loc)

    def count(self, states: Node) -> int:
        return self.m.count(states, self.cur)

    def check_constructive(self) -> None:
        """Refuse the program where a signal test is undecided in a reachable state."""
        for where, loc, name in self.circuit.undecided:
            if (where & self.reachable & self.circuit.relations) != self.m.false:
                raise _non_causal(name, loc)

    # ------------------------------------------------------------------ atoms
    def _sites(self) -> None:
        c = self.circuit
        m = self.m
        ranges: dict[int, list[tuple[int, int]]] = {}
        for label, lo, hi in c.prep.marks:
            if isinstance(label, RtLabel):
                ranges.setdefault(label.site, []).append((lo, hi))
        self.site_task = {s.number: s.task for s in self.composition.sites}
        for site in self.composition.sites:
            spans = ranges.get(site.number, [])
            self.site_active[site.number] = m.any(c.selected(lo, hi) for lo, hi in spans)
            self.site_active_next[site.number] = m.any(c.selected_next(lo, hi)
                                                       for lo, hi in spans)

    def output(self, name: str) -> Node:
        """Where output ``name`` is emitted in the instant (false if no such output)."""
        for decl, node in self.circuit.emitted.items():
            if decl.name == name:
                return node & self.running
        return self.m.false

    def input(self, name: str) -> Node:
        for index, decl in enumerate(self.composition.automaton.inputs):
            if decl.name == name:
                return self.m.var(input_var(index))
        return self.m.false

    def signal(self, name: str) -> Node:
        """Where signal ``name`` is present: an input given, or an output emitted."""
        return self.input(name) | self.output(name)

    def active(self, task: str) -> Node:
        """Where Robot-Task ``task`` is active after the instant."""
        return self.m.any(node for site, node in self.site_active_next.items()
                          if self.site_task[site] == task)

    def status(self, name: str) -> Node:
        """Where the instant's status is ``name`` (``done``, ``failed``, ``aborted``,
        ``ended`` for the end of an ``on fatal`` block)."""
        program = self.composition.automaton.program
        m = self.m
        aborted = self.circuit.emitted[program.aborted] if program.aborted else m.false
        failed = self.circuit.emitted[program.failed] if program.failed else m.false
        failed = failed & ~aborted
        ends = self.circuit.code0 & ~aborted & ~failed & self.running
        fb = m.var(FAILED_BEFORE)
        return {Status.ABORTED: aborted & self.running, Status.FAILED: failed & self.running,
                Status.DONE: ends & ~fb, "ended": ends & fb}.get(name, m.false)

    # ------------------------------------------------------------------ fairness
    def _fairness_sets(self) -> None:
        m = self.m
        for site in self.composition.sites:
            start = self.output(f"{site.task}.start")
            goes_on = (self.site_active[site.number] & self.site_active_next[site.number]
                       & ~start)
            self.fairness.append(f"{site.task} started at {site.loc} ends")
            self.fair_sets.append(~goes_on)
        for number, test in enumerate(self.composition.automaton.data_tests):
            if data.is_clock_test(test.expr):
                evaluated = self.circuit.evaluated.get(number, m.false) & self.running
                self.fairness.append(f"the timer at {test.loc} expires")
                self.fair_sets.append(~evaluated | m.var(f"d{number}"))


def _non_causal(name: str, loc: SourceLocation) -> OrccadError:
    return OrccadError(f"non-causal program: the status of signal {name} cannot be decided in "
                       "this instant (it depends on itself)", loc)


def widest_par(circuit: Circuit) -> str:
    """The ``par`` whose branches hold the most pauses: where the states multiply."""
    best = None
    stack = [circuit.prep.root]
    while stack:
        node = stack.pop()
        if isinstance(node.src, ir.Par):
            sizes = [child.hi - child.lo for child in node.children]
            busy = sum(1 for size in sizes if size)
            if busy >= 2 and (best is None or busy > best[0]):
                best = (busy, node, sizes)
        stack.extend(node.children)
    if best is None:
        return "it has no parallel branches with pauses"
    busy, node, sizes = best
    return (f"the {busy} parallel branches at {node.src.loc} ({', '.join(map(str, sizes))} "
            "pauses each) multiply its states")
