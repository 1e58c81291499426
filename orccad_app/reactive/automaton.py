"""The compiled automaton: explicit states, each with a reaction tree.

A state's reaction is a decision tree, read from the root at each instant:

- :class:`InputTest` branches on the presence of an input signal;
- :class:`DataBranch` branches on a data test (a counter, a timer, ``?S < 20``) evaluated at
  that point, after the actions above it;
- :class:`Action` performs an assignment or a valued emission, then goes on;
- :class:`Leaf` ends the instant: the output signals emitted, the program's status and the
  next state.

A path from the root to a leaf is one *transition* (:func:`transitions`): its guard is the
conjunction of the tests on the path. The tree is deterministic and complete by construction.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Iterator, Union

from orccad_app.diagnostics import SourceLocation
from orccad_app.reactive import ir
from orccad_app.reactive.status import Status

__all__ = [
    "InputTest", "DataBranch", "Action", "Leaf", "Node", "Transition", "Automaton",
    "transitions", "TERMINAL",
]

#: The control-state key of a terminated program, while compiling.
TERMINAL = ("terminated",)


@dataclass(frozen=True, slots=True)
class Leaf:
    target: object  # a state number once compiled (a control-state key while exploring)
    emitted: tuple[ir.SignalDecl, ...]  # outputs, in declaration order
    status: Status = Status.RUNNING


@dataclass(frozen=True, slots=True)
class InputTest:
    signal: ir.SignalDecl
    then: "Node"
    orelse: "Node"


@dataclass(frozen=True, slots=True)
class DataBranch:
    number: int  # index into Automaton.data_tests
    then: "Node"
    orelse: "Node"


@dataclass(frozen=True, slots=True)
class Action:
    """``kind`` is ``assign`` (target: VarDecl) or ``emit`` (target: a valued SignalDecl)."""

    kind: str
    target: object
    expr: ir.Expr
    next: "Node"


Node = Union[Leaf, InputTest, DataBranch, Action]


@dataclass(frozen=True, slots=True)
class Transition:
    """One path of a reaction tree."""

    source: int
    inputs: tuple[tuple[ir.SignalDecl, bool], ...]
    data: tuple[tuple[int, bool], ...]
    actions: tuple[Action, ...]
    emitted: tuple[ir.SignalDecl, ...]
    status: Status
    target: int


@dataclass(frozen=True)
class Automaton:
    """A deterministic, minimized automaton compiled from a reactive program.

    ``trees[i]`` is the reaction of state ``i``; state 0 is the initial state.
    ``waiting[i]`` lists where in the source the program is paused in state ``i``;
    ``labels[i]`` the labels of the marked regions it is in (e.g. active Robot-Task phases).
    ``terminal`` is the number of the state of a terminated program, if reachable.
    """

    program: ir.Program
    trees: tuple[Node, ...]
    waiting: tuple[tuple[SourceLocation, ...], ...]
    data_tests: tuple[ir.DataTest, ...]
    variables: tuple[ir.VarDecl, ...]
    labels: tuple[frozenset, ...] = ()
    terminal: int | None = None
    initial: int = 0

    @property
    def name(self) -> str:
        return self.program.name

    @property
    def inputs(self) -> tuple[ir.SignalDecl, ...]:
        return self.program.inputs

    @property
    def outputs(self) -> tuple[ir.SignalDecl, ...]:
        return self.program.outputs

    @property
    def state_count(self) -> int:
        return len(self.trees)

    def transitions(self) -> Iterator[Transition]:
        for state, tree in enumerate(self.trees):
            yield from transitions(state, tree)

    @property
    def transition_count(self) -> int:
        return sum(1 for _ in self.transitions())


def transitions(state: int, tree: Node) -> Iterator[Transition]:
    """The root-to-leaf paths of ``tree``, then-branches first."""
    stack: list[tuple[Node, tuple, tuple, tuple]] = [(tree, (), (), ())]
    while stack:
        node, inputs, data, actions = stack.pop()
        if isinstance(node, Leaf):
            yield Transition(state, inputs, data, actions, node.emitted, node.status,
                             node.target)  # type: ignore[arg-type]
        elif isinstance(node, InputTest):
            stack.append((node.orelse, inputs + ((node.signal, False),), data, actions))
            stack.append((node.then, inputs + ((node.signal, True),), data, actions))
        elif isinstance(node, DataBranch):
            stack.append((node.orelse, inputs, data + ((node.number, False),), actions))
            stack.append((node.then, inputs, data + ((node.number, True),), actions))
        else:
            stack.append((node.next, inputs, data, actions + (node,)))
