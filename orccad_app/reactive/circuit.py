"""The circuit of a reactive program: its instant as boolean functions, evaluated on BDDs.

Esterel v5's translation (Berry, *The Constructive Semantics of Pure Esterel*, ch. 11–12):
one register per ``pause`` and per signal whose ``pre`` is read, and, for the instant, a
wire per statement activation, completion code and signal. The wires are built by walking
the prepared kernel (:mod:`orccad_app.reactive.prepare`) the way the explicit engine walks it
(:mod:`orccad_app.reactive.walk`), statement by statement, but with BDDs over the registers,
the inputs and the data tests instead of one state and one valuation:

- every *visit* of a statement (its surface, started in the instant, or its depth, resumed
  from its registers; a loop's body is visited in depth and again in surface when it
  restarts; a sequence's later children once as the continuation of its depth) has its own
  wires, so a statement run twice in one instant (a loop restarted by an enclosing one, the
  old and the new incarnation of a local signal) is two sub-circuits, as the engine walks it
  twice: the circuit is the engine's instant, tabulated for all states at once;
- values are *dual rail*: a pair (must, can) of BDDs, as the engine's must/can analysis.
  Signal statuses are the least fixpoint of the walks (present where they must be emitted,
  absent where they cannot be); the program is constructive where every signal a test reads
  is decided; where it is not, in a reachable state, the program is refused (located at the
  test), as the explicit compiler refuses it;
- data tests are free variables, one per test and instant (the checker's data abstraction),
  and data actions are not evaluated: this circuit is the control of the program. Where each
  data action and data test is reached is recorded (:class:`Activation`, in the walk's order,
  with its sure activation in every walk) for the C generator, which runs them
  (:mod:`orccad_app.codegen.circuit_schedule`).

The result (:class:`Circuit`) gives the next value of every register, the outputs emitted,
the completion of the program and what the checker's atoms and fairness sets read.

This module holds the circuit's vocabulary (variable names, :class:`Circuit`);
:mod:`.circuit_walk` is one symbolic walk, :mod:`.circuit_build` iterates the walks to the
fixpoint and builds the circuit (:func:`~.circuit_build.build_circuit`).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from orccad_app.diagnostics import SourceLocation
from orccad_app.reactive import ir
from orccad_app.reactive.prepare import KNode, Prepared
from orccad_app.reactive.bdd import Manager, Node

__all__ = ["Activation", "Circuit", "Rail", "counter_bit", "register", "pre_bit", "input_var", "data_var",
           "BOOT", "TERM", "FAILED_BEFORE", "next_name"]

BOOT, TERM, FAILED_BEFORE = "boot", "term", "failed_before"


def register(pid: int) -> str:
    return f"r{pid}"


def pre_bit(k: int) -> str:
    return f"q{k}"


def input_var(index: int) -> str:
    return f"i{index}"


def data_var(number: int) -> str:
    return f"d{number}"


def counter_bit(k: int, bit: int) -> str:
    """Bit ``bit`` of the ``k``-th tracked variable's register."""
    return f"v{k}_{bit}"


def next_name(name: str) -> str:
    return name + "_n"


Rail = tuple[Node, Node]
"""A dual-rail value: (where it is sure, where it may be)."""


@dataclass
class Activation:
    """One visit of a data action or data test in the walk (what the engine records as an
    event, :meth:`orccad_app.reactive.walk.Walk.record`).

    ``kind``: ``assign``, ``emit`` (a valued emission), ``init`` (a valued local signal's new
    incarnation) or ``test``; ``visit`` numbers the visit (the same in every walk), ``node``
    is the statement (for a test: the statement whose test reads it), ``sure`` where it runs;
    ``target`` the variable, signal or data-test number; ``expr`` the expression (a signal's
    ``pre`` in its fresh incarnation already replaced, as the engine does); ``key`` the
    signal's incarnation (locals: ``(decl, depth)``); ``reads`` the incarnations whose value
    it reads.
    """

    kind: str
    visit: int
    node: KNode
    sure: Node
    target: object
    expr: ir.Expr | None
    key: object = None
    reads: tuple = ()


@dataclass
class Circuit:
    """The instant of a program as functions of the registers, inputs and data tests.

    Every function holds only where the program has not terminated (``term`` false).
    ``next`` gives each register's next value (registers: ``boot``, ``term``,
    ``failed_before``, pauses, ``pre`` bits), ``emitted`` each output's presence, ``code0``
    where the program terminates in the instant, ``evaluated`` where each data test is
    evaluated, ``undecided`` where a signal test cannot be decided (with the test's location).
    """

    prep: Prepared
    manager: Manager
    registers: list[str]
    inputs: list[str]
    data: list[str]
    next: dict[str, Node] = field(default_factory=dict)
    emitted: dict[ir.SignalDecl, Node] = field(default_factory=dict)
    code0: Node = None
    evaluated: dict[int, Node] = field(default_factory=dict)
    undecided: list[tuple[Node, SourceLocation, str]] = field(default_factory=list)
    relations: Node = None
    walks: int = 0
    tracked: tuple[ir.VarDecl, ...] = ()
    overflow: Node = None
    """Where a tracked variable's value leaves its bits (the counters are then abstracted)."""
    #: the data actions and tests of the last walk, in its order
    activations: list[Activation] = field(default_factory=list)
    #: for each walk, the sure activation of each visit (by ``Activation.visit``)
    activation_rounds: list[dict[int, Node]] = field(default_factory=list)
    _visits: dict[tuple, int] = field(default_factory=dict)

    def visit_id(self, parent: int, index: int, depth: bool) -> int:
        """The number of the visit of statement ``index`` (in depth or not) inside visit
        ``parent``: the same in every walk."""
        key = (parent, index, depth)
        number = self._visits.get(key)
        if number is None:
            number = self._visits[key] = len(self._visits) + 1
        return number

    def selected(self, lo: int, hi: int) -> Node:
        """Where a current register of the pauses ``[lo, hi)`` is set."""
        m = self.manager
        return m.any(m.var(register(p)) for p in range(lo, hi))

    def selected_next(self, lo: int, hi: int) -> Node:
        """Where a register of the pauses ``[lo, hi)`` is set after the instant."""
        return self.manager.any(self.next[register(p)] for p in range(lo, hi))
