"""The meaning of atoms in one instant (one step of the model): the instant's *letter*.

An instant is one step. Its letter is the set of atoms true in it:

==================  ===========================================================================
``S`` (a signal)    an input present (tested true by the step's guard, or chosen, see below)
                    or an output emitted in the instant
``started(X)``      ``X.start`` is emitted (an instance of Robot-Task X starts)
``ended(X)``        ``X.good_end`` is emitted (its good end)
``raised(E)``       ``E.raised`` is emitted (exception E is raised, type 2 or 3)
``active(X)``       the state *after* the instant is inside an instance of X
                    (it has an ``RtLabel(X, site)``): true from the instant X starts,
                    false from the instant it ends, raises or is killed
``done``            the mission terminates normally in the instant
``failed``          an uncaught type-2 exception ends the mission in the instant
``aborted``         a type-3 exception aborts the mission in the instant
==================  ===========================================================================

So ``run A; run B`` satisfies ``always not (active(A) and active(B))`` (in the instant A
ends and B starts, only B is active after it) and ``always (started(B) -> once ended(A))``
(``once`` includes the present instant).

A step's guard tests only the inputs its state looks at; the others are *free*. Free inputs
that the formulas mention are expanded: the step gives one letter per choice of their
presence, so a property cannot rely on an untested input being absent.
"""

from __future__ import annotations

from itertools import product

from orccad_app.verify.model import Model, Step

__all__ = ["Alphabet"]


class Alphabet:
    """Atoms numbered as bits; the letters of each step as bit masks."""

    def __init__(self, model: Model, keys):
        self.model = model
        self.keys: list[tuple] = sorted(set(keys))
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
        mask = 0
        active = self.model.active_tasks(step.target) if self.model.states else frozenset()
        for key, bit in self.bit.items():
            kind, name = key
            if kind == "sig":
                true = name in step.emitted or guard.get(name, False)
            elif kind == "started":
                true = f"{name}.start" in step.emitted
            elif kind == "ended":
                true = f"{name}.good_end" in step.emitted
            elif kind == "raised":
                true = f"{name}.raised" in step.emitted
            elif kind == "active":
                true = name in active
            else:
                true = step.status == name
            if true:
                mask |= 1 << bit
        return mask

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
