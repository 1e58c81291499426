"""Concrete runs out of BDDs: shortest runs to a set of steps, and runs inside a set.

A concrete instant (:class:`Point`) is one valuation of the current registers, the inputs and
the data tests (and, in a product with a tableau, its current and next bits). Shortest runs
use the breadth-first rings of the exploration: the first ring that has a step in the goal,
then back ring by ring, each time a state with a step into the one after.
"""

from __future__ import annotations

from dataclasses import dataclass

from orccad_app.reactive.bdd import Node
from orccad_app.verify.symbolic.model import SymbolicModel

__all__ = ["Point", "shortest_run", "state_of", "pick_state"]


@dataclass(frozen=True)
class Point:
    """One instant of a concrete run: variable name -> value (registers, inputs, data)."""

    values: tuple[tuple[str, bool], ...]

    def get(self, name: str) -> bool:
        return dict(self.values).get(name, False)

    def as_dict(self) -> dict[str, bool]:
        return dict(self.values)


def state_of(model: SymbolicModel, point: dict[str, bool]) -> Node:
    """The cube of the current registers of ``point``."""
    return model.m.cube({r: point.get(r, False) for r in model.cur})


def pick_state(model: SymbolicModel, states: Node) -> dict[str, bool]:
    return model.m.pick(states, model.cur)


def _point(model: SymbolicModel, steps: Node) -> dict[str, bool]:
    return model.m.pick(steps, model.cur + model.free)


def shortest_run(model: SymbolicModel, goal: Node) -> list[Point] | None:
    """The shortest run from the initial state whose last step is in ``goal`` (a BDD over
    the current registers, inputs and data tests), or None."""
    m = model.m
    relations = model.circuit.relations
    for index, ring in enumerate(model.rings):
        hit = ring & goal & relations
        if hit == m.false:
            continue
        last = _point(model, hit)
        run = [last]
        target = state_of(model, last)
        for earlier in reversed(model.rings[:index]):
            step = model.step_relation(earlier, target)
            point = _point(model, step)
            run.append(point)
            target = state_of(model, point)
        run.reverse()
        return [Point(tuple(sorted(p.items()))) for p in run]
    return None


def next_state(model: SymbolicModel, point: dict[str, bool]) -> dict[str, bool]:
    """The registers after the instant ``point``."""
    m = model.m
    values = {name: (m.true if value else m.false) for name, value in point.items()
              if m.has(name)}
    return {r: m.bdd.let(values, f) == m.true for r, f in model.functions.items()}


def holds_at(model: SymbolicModel, node: Node, point: dict[str, bool]) -> bool:
    """Whether the BDD ``node`` holds at ``point`` (every variable it reads given)."""
    m = model.m
    values = {name: (m.true if value else m.false) for name, value in point.items()
              if m.has(name)}
    return m.bdd.let(values, node) == m.true
