"""The reachable states of a circuit, to simplify what the generated C computes.

The step of the circuit's C only ever sees reachable register valuations (it starts at boot
and computes each next valuation), so the static-order checks of :mod:`.circuit_schedule`
need hold only there (``missions/arm_recovery.orc``'s counter is ordered only there), and
every function it evaluates may be replaced by any function equal to it there: CUDD's
*restrict* (Coudert and Madre's generalized cofactor) with the reachable states as care set
shrinks the BDDs where registers exclude each other (one pause of a sequence at a time).
A restricted function may read a data test where the original did not (outside the care
set): the step writes a wire again once a test it reads is evaluated (:mod:`.circuit`).

The image is the symbolic checker's (:mod:`orccad_app.verify.symbolic.model`, a layer this
one may not import): one conjunct ``r' <-> f_r`` per register, each current variable
quantified after the last conjunct that reads it. A budget of images and BDD nodes keeps it
bounded; past it the care set is every state (nothing simplified).
"""

from __future__ import annotations

from orccad_app.reactive.bdd import Node
from orccad_app.reactive.circuit import BOOT, Circuit, next_name

try:  # pragma: no cover - which backend is installed
    from dd.cudd import restrict as _restrict
except ImportError:  # pragma: no cover
    _restrict = None


__all__ = ["reachable", "simplify", "MAX_IMAGES", "MAX_NODES"]

#: breadth-first images tried before giving up (the care set is then every state)
MAX_IMAGES = 10_000
#: BDD nodes the manager may hold during the search
MAX_NODES = 2_000_000


def reachable(circuit: Circuit) -> Node:
    """The reachable register valuations, or ``true`` past the budget."""
    m = circuit.manager
    cur = list(circuit.registers)
    to_cur = {next_name(r): r for r in cur}
    free = set(cur) | set(circuit.inputs) | set(circuit.data)
    parts = [circuit.relations] + [m.var(next_name(r)).equiv(circuit.next[r]) for r in cur]
    last: dict[str, int] = {}
    for index, part in enumerate(parts):
        for name in m.support(part) & free:
            last[name] = index
    after: list[list[str]] = [[] for _ in parts]
    for name, index in last.items():
        after[index].append(name)
    never = [n for n in free if n not in last]
    reached = frontier = m.cube({r: r == BOOT for r in cur})
    for _ in range(MAX_IMAGES):
        image = m.exists(never, frontier)
        for part, names in zip(parts, after):
            image = image & part
            if names:
                image = m.exists(names, image)
        new = m.rename(image, to_cur) & ~reached
        if new == m.false:
            return reached
        if len(m.bdd) > MAX_NODES:
            break
        reached = reached | new
        frontier = new
    return m.true


def simplify(f: Node, care: Node) -> Node:
    """A function equal to ``f`` wherever ``care`` holds, with a BDD no larger (``f`` itself
    without CUDD)."""
    if _restrict is None or care == care.bdd.true:
        return f
    g = _restrict(f, care)
    return g if g.dag_size < f.dag_size else f
