"""The meaning of atoms in one instant (one step of the model): the instant's *letter*.

An instant is one step. Its letter is the set of atoms true in it, as
:mod:`orccad_app.robottask.atoms` defines them (the run monitor reads the same definitions):
a signal is present when the step's guard tests it true (or it is chosen, see below) or the
step emits it; ``active(X)`` reads the state after the step; ``done`` / ``failed`` /
``aborted`` are the step's status (the end of an ``on fatal`` block is no ``done``:
:data:`~orccad_app.verify.model.ENDED`).

So ``run A; run B`` satisfies ``always not (active(A) and active(B))`` (in the instant A
ends and B starts, only B is active after it) and ``always (started(B) -> once ended(A))``
(``once`` includes the present instant).

A step's guard tests only the inputs its state looks at; the others are *free*. Free inputs
that the formulas mention are expanded: the step gives one letter per choice of their
presence, so a property cannot rely on an untested input being absent.
"""

from __future__ import annotations

from itertools import product

from orccad_app.robottask.atoms import Atoms, InstantView
from orccad_app.verify.model import Model, Step

__all__ = ["Alphabet"]


class Alphabet:
    """Atoms numbered as bits; the letters of each step as bit masks."""

    def __init__(self, model: Model, keys):
        self.model = model
        self.atoms = Atoms(model.composition.roles, keys)
        self.keys: list[tuple] = self.atoms.keys
        self.bit = {key: i for i, key in enumerate(self.keys)}
        inputs = {s.name for s in model.automaton.inputs}
        self.inputs = [name for kind, name in self.keys if kind == "sig" and name in inputs]
        self._cache: dict[int, list[tuple[int, tuple[str, ...]]]] = {}

    def letters(self, step: Step) -> list[tuple[int, tuple[str, ...]]]:
        """``(mask, chosen)`` per letter of ``step``: ``chosen`` lists the free inputs taken
        present in that letter."""
        cached = self._cache.get(id(step))
        if cached is not None and cached[0] is step:
            return cached[1]
        guard = dict(step.path.guard) if step.path is not None else {}
        base = self._base(step, guard)
        free = [name for name in self.inputs if name not in guard]
        found = []
        relations = self.model.automaton.program.relations
        for choice in product((False, True), repeat=len(free)):
            chosen = tuple(name for name, on in zip(free, choice) if on)
            if relations and not _possible(relations, {**guard, **dict(zip(free, choice))}):
                continue  # the environment never gives these inputs (a relation)
            mask = base
            for name in chosen:
                mask |= 1 << self.bit[("sig", name)]
            found.append((mask, chosen))
        self._cache[id(step)] = (step, found)  # type: ignore[assignment]
        return found

    def _base(self, step: Step, guard: dict) -> int:
        present = step.emitted | {name for name, on in guard.items() if on}
        instant = InstantView(present, lambda: self._active(step), step.status)
        mask = 0
        for key in self.atoms.letter(instant):
            mask |= 1 << self.bit[key]
        return mask

    def _active(self, step: Step) -> frozenset[str]:
        return self.model.active_tasks(step.target) if self.model.states else frozenset()

    def letter_set(self, mask: int) -> frozenset:
        """The atoms true in a letter."""
        return frozenset(key for key, bit in self.bit.items() if mask >> bit & 1)


def _possible(relations, known: dict) -> bool:
    """Whether some presence of the inputs not in ``known`` (name -> present) satisfies
    every relation."""
    for relation in relations:
        values = [known.get(s.name) for s in relation.signals]
        if relation.kind == "#" and sum(v is True for v in values) > 1:
            return False
        if relation.kind == "=>" and values[0] is True and values[1] is False:
            return False
    return True
