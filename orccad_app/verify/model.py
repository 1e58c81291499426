"""The model that properties are checked on: the composed automaton with its data abstracted.

A *model state* is ``(automaton state, values of the tracked variables, failed-before)``;
a *step* is one instant: one root-to-leaf path of the state's reaction tree whose data tests
agree with the tracked values (tests on untracked data may go either way, see
:mod:`orccad_app.verify.data`). The failed-before flag remembers that the mission failed or
was aborted, so the end of an ``on fatal`` block is not a ``done``.

After the mission has ended, the model *stutters*: the terminal state repeats an instant in
which no output is emitted, no task is active and the status atoms are false (inputs are
still free: the environment goes on). Every path is therefore infinite.

*Environment fairness* is a set of edge sets (generalized Büchi conditions); a path is fair
when it takes an edge of each set infinitely often:

- for each ``run`` site: an edge on which that instance of the Robot-Task does not go on
  (it is not active before or after the instant, or it is started again in the instant):
  every started RT eventually ends, raises or is killed;
- for each timer test (a data test reading the clock): an edge on which the test is not
  evaluated or is true: time diverges, so an awaited duration eventually elapses.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from orccad_app.diagnostics import OrccadError
from orccad_app.lang.limits import MAX_INT, MIN_INT
from orccad_app.reactive import ir
from orccad_app.reactive.automaton import Action, DataBranch, InputTest, Leaf, Node
from orccad_app.reactive.status import Status
from orccad_app.verify import data
from orccad_app.robottask.composition import Composition
from orccad_app.robottask.labels import RtLabel

__all__ = ["Path", "Step", "Model", "build_model", "MODEL_BUDGET", "ENDED"]

#: Model states explored with exact counters before falling back to fully abstract data.
MODEL_BUDGET = 100_000
#: Status of the instant in which an ``on fatal`` block ends (the mission had been aborted).
ENDED = "ended"


@dataclass(frozen=True, slots=True)
class Path:
    """One root-to-leaf path of a reaction tree, its events in execution order:
    ``("in", signal, present)``, ``("test", number, outcome)``, ``("act", action)``."""

    events: tuple
    leaf: Leaf
    guard: tuple[tuple[str, bool], ...]


@dataclass(frozen=True, slots=True)
class Step:
    """One instant of the model, from model state ``source`` to ``target``.

    ``status`` is ``running``, ``done``, ``failed``, ``aborted``, :data:`ENDED`, or ``None``
    for a stutter instant after the end. ``fair`` has bit i set when the step is in
    fairness set i.
    """

    source: int
    target: int
    path: Path | None
    emitted: frozenset[str]
    status: str | None
    fair: int


@dataclass
class Model:
    """The reachable model states and their steps; state 0 is initial."""

    composition: Composition
    tracked: tuple[ir.VarDecl, ...]
    states: list[tuple] = field(default_factory=list)        # (q, values, failed_before)
    steps: list[list[Step]] = field(default_factory=list)
    fairness: list[str] = field(default_factory=list)         # names of the fairness sets
    exact: bool = True                                         # counters tracked exactly
    abstracted_because: str | None = None                      # why not, when not exact

    @property
    def automaton(self):
        return self.composition.automaton

    @property
    def full_fairness(self) -> int:
        return (1 << len(self.fairness)) - 1

    def control(self, state: int) -> int:
        """The automaton state of a model state."""
        return self.states[state][0]

    def labels(self, state: int) -> frozenset:
        labels = self.automaton.labels
        return labels[self.control(state)] if labels else frozenset()

    def sites(self, state: int) -> frozenset[int]:
        """Numbers of the ``run`` sites whose task instance is active in ``state``."""
        return frozenset(label.site for label in self.labels(state) if isinstance(label, RtLabel))

    def active_tasks(self, state: int) -> frozenset[str]:
        return frozenset(label.task for label in self.labels(state) if isinstance(label, RtLabel))

    def is_end(self, state: int) -> bool:
        return self.control(state) == self.automaton.terminal

    @property
    def step_count(self) -> int:
        return sum(len(s) for s in self.steps)


def tree_paths(tree: Node) -> list[Path]:
    """Every root-to-leaf path of ``tree``, then-branches first."""
    found: list[Path] = []
    stack: list[tuple[Node, tuple, tuple]] = [(tree, (), ())]
    while stack:
        node, events, guard = stack.pop()
        if isinstance(node, Leaf):
            found.append(Path(events, node, guard))
        elif isinstance(node, InputTest):
            name = node.signal.name
            stack.append((node.orelse, events + (("in", node.signal, False),),
                          guard + ((name, False),)))
            stack.append((node.then, events + (("in", node.signal, True),),
                          guard + ((name, True),)))
        elif isinstance(node, DataBranch):
            stack.append((node.orelse, events + (("test", node.number, False),), guard))
            stack.append((node.then, events + (("test", node.number, True),), guard))
        else:
            assert isinstance(node, Action)
            stack.append((node.next, events + (("act", node),), guard))
    return found


class _Builder:
    def __init__(self, composition: Composition, tracked: tuple[ir.VarDecl, ...],
                 budget: int):
        self.model = Model(composition, tracked)
        self.automaton = composition.automaton
        self.budget = budget
        self.paths = [tree_paths(tree) for tree in self.automaton.trees]
        self.index: dict[tuple, int] = {}
        self._fairness_sets()

    def _fairness_sets(self) -> None:
        model = self.model
        self.site_bit = {}
        for site in model.composition.sites:
            self.site_bit[site.number] = len(model.fairness)
            model.fairness.append(f"{site.task} started at {site.loc} ends")
        self.timer_bit = {}
        for number, test in enumerate(self.automaton.data_tests):
            if data.is_clock_test(test.expr):
                self.timer_bit[number] = len(model.fairness)
                model.fairness.append(f"the timer at {test.loc} expires")
        self.site_task = {s.number: s.task for s in model.composition.sites}

    def state(self, key: tuple) -> int:
        number = self.index.get(key)
        if number is None:
            if len(self.index) >= self.budget:
                raise _OverBudget
            number = self.index[key] = len(self.model.states)
            self.model.states.append(key)
            self.model.steps.append([])
        return number

    def build(self) -> Model:
        model = self.model
        initial = (self.automaton.initial, (0,) * len(model.tracked), False)
        self.state(initial)
        done = 0
        while done < len(model.states):
            model.steps[done] = self.steps_of(done)
            done += 1
        return model

    def steps_of(self, number: int) -> list[Step]:
        q, values, failed_before = self.model.states[number]
        if q == self.automaton.terminal:
            return [Step(number, number, None, frozenset(), None, self.model.full_fairness)]
        steps = []
        for path in self.paths[q]:
            after = self._run(path, values)
            if after is None:
                continue
            leaf = path.leaf
            status = leaf.status
            if status == Status.DONE and failed_before:
                status = ENDED
            target = self.state((leaf.target, after,
                                 failed_before or status in (Status.FAILED, Status.ABORTED)))
            emitted = frozenset(s.name for s in leaf.emitted if not s.name.startswith("_"))
            steps.append(Step(number, target, path, emitted, status,
                              self._fair(q, path, leaf, emitted)))
        return steps

    def _run(self, path: Path, values: tuple) -> tuple | None:
        """The tracked values after ``path``, or None if its data tests contradict them."""
        tracked = self.model.tracked
        if not tracked and not any(e[0] == "test" for e in path.events):
            return values
        env = dict(zip(tracked, values))
        for event in path.events:
            if event[0] == "test":
                value = data.evaluate(self.automaton.data_tests[event[1]].expr, env)
                if value is not data.TOP and bool(value) != event[2]:
                    return None
            elif event[0] == "act" and event[1].kind == "assign" and event[1].target in env:
                value = data.evaluate(event[1].expr, env)
                if type(value) is int and not MIN_INT <= value <= MAX_INT:
                    raise _OverBudget(f"'{event[1].target.name}' leaves the 64-bit integers "
                                      f"[{MIN_INT}, {MAX_INT}]")
                env[event[1].target] = value
        return tuple(env[v] for v in tracked)

    def _fair(self, q: int, path: Path, leaf: Leaf, emitted: frozenset[str]) -> int:
        mask = self.model.full_fairness
        labels = self.automaton.labels
        before = labels[q] if labels else frozenset()
        after = labels[leaf.target] if labels else frozenset()
        for label in before & after:
            if isinstance(label, RtLabel) and f"{label.task}.start" not in emitted:
                mask &= ~(1 << self.site_bit[label.site])
        for event in path.events:
            if event[0] == "test" and not event[2] and event[1] in self.timer_bit:
                mask &= ~(1 << self.timer_bit[event[1]])
        return mask


class _OverBudget(Exception):
    pass


def build_model(composition: Composition, *, budget: int = MODEL_BUDGET,
                counters: bool = True) -> Model:
    """Explore the model of ``composition``: counters exactly when the state space stays
    under ``budget`` states (and ``counters``), else every data value abstracted."""
    counted = data.tracked_variables(composition.automaton)
    tracked = counted if counters else ()
    reason = None if counters or not counted else "counters abstracted on request"
    if tracked:
        try:
            return _Builder(composition, tracked, budget).build()
        except _OverBudget as over:
            reason = str(over) if over.args else f"more than {budget} states with exact counters"
    try:
        model = _Builder(composition, (), budget).build()
    except _OverBudget:  # pragma: no cover - at most twice the automaton's states
        raise OrccadError(f"mission {composition.name}: the model has more than {budget} "
                          "states", composition.mission.loc) from None
    model.exact = not counted
    model.abstracted_because = reason
    return model
