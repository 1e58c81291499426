"""A tableau for LTL with past (Lichtenstein–Pnueli–Zuck), built on the fly.

The closure of a formula has *elementary* formulas whose truth is not a function of the
instant's letter: ``X g`` for each ``next g`` and ``X (a U b)`` for each until (the *next*
bits), ``Y g`` for each ``previously g`` and ``Y (a S b)`` for each since (the *previous*
bits). Given the letter ``L``, the previous bits ``Y`` and a guess of the next bits ``X``,
every subformula's truth follows by the expansion laws::

    a U b  =  b or (a and X (a U b))         a S b  =  b or (a and Y (a S b))

A tableau state is ``(Y, X_prev)``: the previous bits (all false at the first instant) and
the guess made at the previous instant, which the present instant must honour (at the first
instant: the formula itself must be true). Fulfilment: each ``a U b`` true at an instant must
see ``b`` later; as a generalized Büchi condition, each until has an acceptance set of the
instants where it is false or ``b`` holds.

Past operators may nest future ones and the converse: the construction is uniform. The
evaluation of one instant is generated as Python code and memoized per ``(L, Y, X_prev)``.
"""

from __future__ import annotations

from orccad_app.verify.formula import F, subformulas
from orccad_app.verify.letters import Alphabet

__all__ = ["Tableau", "MAX_NEXT_BITS"]

#: Guessed next bits allowed per formula (2^n guesses per instant).
MAX_NEXT_BITS = 14


class Tableau:
    """The on-the-fly tableau of ``formula`` over an :class:`Alphabet`."""

    def __init__(self, formula: F, alphabet: Alphabet):
        self.formula = formula
        nodes = subformulas(formula)
        self.nexts = [g for g in nodes if g.op in ("X", "U")]
        self.prevs = [g for g in nodes if g.op in ("Y", "S")]
        self.untils = [g for g in nodes if g.op == "U"]
        if len(self.nexts) > MAX_NEXT_BITS:
            from orccad_app.diagnostics import OrccadError
            raise OrccadError(f"formula too large for the checker: {len(self.nexts)} "
                              f"future operators (at most {MAX_NEXT_BITS})")
        self._evaluate = self._generate(nodes, alphabet)
        self._guesses = range(1 << len(self.nexts))
        self._table: dict[tuple, list[tuple[int, int, int]]] = {}

    @property
    def acceptance_count(self) -> int:
        return len(self.untils)

    def _generate(self, nodes: list[F], alphabet: Alphabet):
        name = {g: f"v{i}" for i, g in enumerate(nodes)}
        xbit = {g: i for i, g in enumerate(self.nexts)}
        ybit = {g: i for i, g in enumerate(self.prevs)}
        lines = ["def evaluate(L, Y, X):"]
        for g in nodes:
            v, a = name[g], name.get(g.left) if g.left is not None else None
            b = name.get(g.right) if g.right is not None else None
            if g.op == "true" or g.op == "false":
                expr = "1" if g.op == "true" else "0"
            elif g.op == "atom":
                expr = f"(L >> {alphabet.bit[g.key]}) & 1"
            elif g.op == "not":
                expr = f"1 - {a}"
            elif g.op == "and":
                expr = f"{a} & {b}"
            elif g.op == "or":
                expr = f"{a} | {b}"
            elif g.op == "X":
                expr = f"(X >> {xbit[g]}) & 1"
            elif g.op == "U":
                expr = f"{b} | ({a} & (X >> {xbit[g]}) & 1)"
            elif g.op == "Y":
                expr = f"(Y >> {ybit[g]}) & 1"
            else:  # S
                expr = f"{b} | ({a} & (Y >> {ybit[g]}) & 1)"
            lines.append(f"    {v} = {expr}")
        targets = [name[g.left] if g.op == "X" else name[g] for g in self.nexts]
        carried = [name[g.left] if g.op == "Y" else name[g] for g in self.prevs]
        accepts = [f"(1 - {name[g]}) | {name[g.right]}" for g in self.untils]
        lines.append(f"    xt = {_bits(targets)}")
        lines.append(f"    yn = {_bits(carried)}")
        lines.append(f"    acc = {_bits(accepts)}")
        lines.append(f"    return {name[self.formula]}, xt, yn, acc")
        scope: dict = {}
        exec("\n".join(lines), scope)  # noqa: S102 - code generated from our own formula
        return scope["evaluate"]

    def successors(self, letter: int, prev: int, required: int | None):
        """``(X, Y_next, acceptance)`` for each guess consistent with the letter, the
        previous bits and the previous guess (``None``: the first instant)."""
        key = (letter, prev, required)
        found = self._table.get(key)
        if found is None:
            found = []
            evaluate = self._evaluate
            for guess in self._guesses:
                root, xt, yn, acc = evaluate(letter, prev, guess)
                if (root == 1) if required is None else (xt == required):
                    found.append((guess, yn, acc))
            self._table[key] = found
        return found

    def values(self, letter: int, prev: int, guess: int) -> int:
        """The truth of the formula at an instant (for tests)."""
        return self._evaluate(letter, prev, guess)[0]


def _bits(values: list[str]) -> str:
    if not values:
        return "0"
    return " | ".join(f"(({v}) << {i})" for i, v in enumerate(values))
