"""LTL with past on the symbolic model: the tableau as BDDs, fair cycles by Emerson–Lei.

The tableau is the explicit checker's (:mod:`orccad_app.verify.tableau`, Lichtenstein–Pnueli–
Zuck) with its bits as variables: a *guess* bit per ``X g`` and per until (its value at the
instant, guessed at that instant and carried to the next, which must honour it) and a
*previous* bit per ``Y g`` and per since. One instant of the product reads the model's step
(atoms as BDDs over the registers, inputs and data tests), the current bits and the new
guesses; every subformula follows by the expansion laws. At the first instant (``boot``) the
goal must hold; each until brings an acceptance set (instants where it is false or its right
side holds), each environment fairness set of the model another.

A counterexample exists when the reachable product has a fair cycle: the greatest fixpoint
``Z = ∧_k E[Z U (Z ∧ EX_k Z)]`` (Emerson–Lei; ``EX_k``: a step of set k) is not empty. The
lasso is extracted from it as NuSMV does: a shortest prefix to ``Z``, then from a state of
``Z`` a shortest path to a step of each set in turn, closed by a path back to where the cycle
started (if there is none, the cycle restarts from where it got to: it moves down the
components of ``Z`` and ends in one that closes).
"""

from __future__ import annotations

from dataclasses import dataclass

from orccad_app.diagnostics import OrccadError
from orccad_app.verify.formula import F, subformulas
from orccad_app.reactive.bdd import Node
from orccad_app.reactive.circuit import BOOT, next_name
from orccad_app.verify.symbolic.model import SymbolicModel

__all__ = ["SymbolicLasso", "find_lasso_symbolic", "MAX_LASSO_ROUNDS"]

#: Restarts of the cycle's construction (each moves down the components of the fair set).
MAX_LASSO_ROUNDS = 1_000


@dataclass(frozen=True)
class SymbolicLasso:
    """A fair run violating the formula: concrete instants (model and tableau variables)."""

    prefix: tuple[dict[str, bool], ...]
    loop: tuple[dict[str, bool], ...]


class _Product:
    def __init__(self, model: SymbolicModel, goal: F, atoms: dict[tuple, Node], fair: bool):
        self.model = model
        m = self.m = model.m
        nodes = subformulas(goal)
        nexts = [g for g in nodes if g.op in ("X", "U")]
        prevs = [g for g in nodes if g.op in ("Y", "S")]
        untils = [g for g in nodes if g.op == "U"]
        self.guess = [f"tx{i}" for i in range(len(nexts))]
        self.prev = [f"ty{j}" for j in range(len(prevs))]
        for name in self.guess + self.prev:
            m.declare(name)
            m.declare(next_name(name))
        self.bits = self.guess + self.prev
        self.bits_next = [next_name(b) for b in self.bits]
        value: dict[F, Node] = {}
        xbit = {g: i for i, g in enumerate(nexts)}
        ybit = {g: j for j, g in enumerate(prevs)}
        for g in nodes:
            if g.op == "true":
                v = m.true
            elif g.op == "false":
                v = m.false
            elif g.op == "atom":
                v = atoms[g.key]
            elif g.op == "not":
                v = ~value[g.left]
            elif g.op == "and":
                v = value[g.left] & value[g.right]
            elif g.op == "or":
                v = value[g.left] | value[g.right]
            elif g.op == "X":
                v = m.var(next_name(self.guess[xbit[g]]))
            elif g.op == "U":
                v = value[g.right] | (value[g.left]
                                      & m.var(next_name(self.guess[xbit[g]])))
            elif g.op == "Y":
                v = m.var(self.prev[ybit[g]])
            else:  # S
                v = value[g.right] | (value[g.left] & m.var(self.prev[ybit[g]]))
            value[g] = v
        honour = m.true
        for g in nexts:
            target = value[g.left] if g.op == "X" else value[g]
            honour &= m.var(self.guess[xbit[g]]).equiv(target)
        carried = m.true
        for g in prevs:
            now = value[g.left] if g.op == "Y" else value[g]
            carried &= m.var(next_name(self.prev[ybit[g]])).equiv(now)
        boot = m.var(BOOT)
        self.relation = carried & ((boot & value[goal]) | (~boot & honour))
        self.relation &= model.circuit.relations
        self.sets = [~value[g] | value[g.right] for g in untils]
        if fair:
            self.sets += list(model.fair_sets)
        self.init = model.init & m.cube({b: False for b in self.bits})
        self.to_cur = {**model.to_cur, **dict(zip(self.bits_next, self.bits))}
        self.quantify = model.cur + model.free + self.bits
        self.rings: list[Node] = []
        self._steps: dict[Node, Node] = {}

    # ------------------------------------------------------------------ steps
    def _steps_into(self, target: Node) -> Node:
        """Steps (current variables, inputs, data, new bits) into ``target`` (the last few
        kept: Emerson–Lei asks the same set once per fairness set)."""
        cached = self._steps.get(target)
        if cached is not None:
            return cached
        if len(self._steps) > 64:
            self._steps.clear()
        m = self.m
        moved = self.model.compose(target)
        support = m.support(moved)
        moved = m.rename(moved, {b: n for b, n in zip(self.bits, self.bits_next) if b in support})
        steps = self._steps[target] = moved & self.relation
        return steps

    def pre(self, target: Node, edges: Node | None = None) -> Node:
        steps = self._steps_into(target)
        if edges is not None:
            steps &= edges
        return self.m.exists(self.model.free + self.bits_next, steps)

    def image(self, states: Node) -> Node:
        m = self.m
        model = self.model
        result = states & self.relation
        for part, names in zip(model.parts, model.after):
            result = result & part
            if names:
                result = m.exists(names, result)
        result = m.exists(self.bits + model.never_read, result)
        return m.rename(result, self.to_cur)

    def explore(self) -> Node:
        """The product's reachable states, breadth first (the rings are kept for the lasso)."""
        m = self.m
        reached = frontier = self.init
        self.rings = [self.init]
        while True:
            new = self.image(frontier) & ~reached
            self.model.check_budget()
            if new == m.false:
                return reached
            reached |= new
            self.rings.append(new)
            frontier = new

    # ------------------------------------------------------------------ fair states
    def fair_states(self, reachable: Node) -> Node:
        """Emerson–Lei's greatest fixpoint inside ``reachable``, each set's constraint applied
        as soon as it is computed (the rounds then converge in fewer passes)."""
        m = self.m
        z = reachable
        while True:
            old = z
            for edges in self.sets or [m.true]:
                w = frontier = z & self.pre(z, edges)
                while frontier != m.false:
                    self.model.check_budget()
                    frontier = z & self.pre(frontier) & ~w
                    w |= frontier
                z = w
                if z == m.false:
                    return z
            if z == old:
                return z

    # ------------------------------------------------------------------ concrete runs
    def _pick_step(self, state: dict[str, bool], into: Node, edges: Node | None) -> dict:
        m = self.m
        cube = m.cube({n: state[n] for n in self.model.cur + self.bits})
        steps = cube & self._steps_into(into)
        if edges is not None:
            steps &= edges
        point = m.pick(steps, self.model.free + self.bits_next)
        return {**state, **point}

    def _after(self, point: dict[str, bool]) -> dict[str, bool]:
        m = self.m
        values = {n: (m.true if v else m.false) for n, v in point.items() if m.has(n)}
        state = {r: m.bdd.let(values, f) == m.true for r, f in self.model.functions.items()}
        for bit, nxt in zip(self.bits, self.bits_next):
            state[bit] = point[nxt]
        return state

    def _path(self, start: dict[str, bool], within: Node, goal_states: Node,
              edges: Node | None) -> list[dict] | None:
        """Shortest path from ``start`` inside ``within`` whose last step is in ``edges``
        (or any step) into ``goal_states``."""
        m = self.m
        cube = m.cube({n: start[n] for n in self.model.cur + self.bits})
        rings = [cube]
        seen = cube
        while True:
            last = rings[-1]
            hit = last & self.pre(goal_states, edges)
            if hit != m.false:
                break
            new = self.image(last) & within & ~seen
            if new == m.false:
                return None
            seen |= new
            rings.append(new)
        states = [self.m.pick(hit, self.model.cur + self.bits)]
        for earlier in reversed(rings[:-1]):
            target = m.cube({n: states[-1][n] for n in self.model.cur + self.bits})
            states.append(m.pick(earlier & self.pre(target), self.model.cur + self.bits))
        states.reverse()
        points = []
        for a, b in zip(states, states[1:]):
            target = m.cube({n: b[n] for n in self.model.cur + self.bits})
            points.append(self._pick_step(a, target, None))
        points.append(self._pick_step(states[-1], goal_states, edges))
        return points

    def lasso(self, fair: Node) -> SymbolicLasso:
        m = self.m
        prefix: list[dict] = []
        entry = next(i for i, ring in enumerate(self.rings) if (ring & fair) != m.false)
        state = m.pick(self.rings[entry] & fair, self.model.cur + self.bits)
        chain = [state]
        for earlier in reversed(self.rings[:entry]):
            target = m.cube({n: chain[-1][n] for n in self.model.cur + self.bits})
            chain.append(m.pick(earlier & self.pre(target), self.model.cur + self.bits))
        chain.reverse()
        for a, b in zip(chain, chain[1:]):
            target = m.cube({n: b[n] for n in self.model.cur + self.bits})
            prefix.append(self._pick_step(a, target, None))
        for _ in range(MAX_LASSO_ROUNDS):
            loop: list[dict] = []
            here = state
            for edges in self.sets:
                path = self._path(here, fair, fair, edges)
                assert path is not None, "a fair state without a step of a fair set"
                loop += path
                here = self._after(path[-1])
            origin = m.cube({n: state[n] for n in self.model.cur + self.bits})
            if loop and here == state:
                return SymbolicLasso(tuple(prefix), tuple(loop))
            back = self._path(here, fair, origin, None)
            if back is not None:
                return SymbolicLasso(tuple(prefix), tuple(loop + back))
            prefix += loop
            state = here
        raise OrccadError("internal error: no fair cycle closes in the symbolic model")


def find_lasso_symbolic(model: SymbolicModel, goal: F, atoms: dict[tuple, Node],
                        fair: bool = True) -> SymbolicLasso | None:
    """A fair run of the model satisfying ``goal`` (the assumptions and the negated
    property), or None when there is none."""
    product = _Product(model, goal, atoms, fair)
    fair_states = product.fair_states(product.explore())
    if fair_states == model.m.false:
        return None
    return product.lasso(fair_states)
