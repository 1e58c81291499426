"""The built-in properties (:mod:`orccad_app.verify.builtins`) on the symbolic model.

Each is a set of bad steps (or states) intersected with the reachable states; a violation
comes with the shortest run to it (:func:`~.runs.shortest_run`), its message written from
that run's last step as the explicit checker writes it.
"""

from __future__ import annotations

from orccad_app.lang import ast
from orccad_app.robottask.application import contains
from orccad_app.verify.builtins import Violation, _endless_spans
from orccad_app.verify.model import Step
from orccad_app.reactive.bdd import Node
from orccad_app.reactive.status import Status
from orccad_app.verify.symbolic.model import SymbolicModel
from orccad_app.verify.symbolic.runs import Point, pick_state, shortest_run
from orccad_app.verify.symbolic.witness import Witness

__all__ = ["check_builtin_symbolic"]


def _steps(witness: Witness, run: list[Point]) -> tuple[Step, ...]:
    return tuple(witness.step(point.as_dict())[0] for point in run)


def _fatal(model: SymbolicModel) -> list[tuple[str, Node]]:
    """(exception, where it is raised) for each type-3 exception of each Robot-Task."""
    found = []
    for task in model.composition.program.robottasks:
        for exc in task.exceptions:
            if exc.type is ast.ExceptionType.FATAL:
                found.append((exc.name, model.input(f"{task.name}.{exc.name}")
                              & model.output(f"{exc.name}.raised")))
    return found


def _sites_outside(model: SymbolicModel, allowed: frozenset[int]) -> Node:
    """Where a site outside ``allowed`` is active after the instant."""
    return model.m.any(node for site, node in model.site_active_next.items()
                       if site not in allowed)


def _fatal_aborts(model: SymbolicModel, witness: Witness) -> Violation | None:
    m = model.m
    allowed = frozenset(s.number for s in model.composition.sites if s.on_fatal)
    raised = m.any(node for _, node in _fatal(model))
    bad = raised & (~model.status(Status.ABORTED) | _sites_outside(model, allowed))
    run = shortest_run(model, bad)
    if run is None:
        return None
    steps = _steps(witness, run)
    last = steps[-1]
    guard = dict(last.path.guard) if last.path is not None else {}
    name = next(exc.name for task in model.composition.program.robottasks
                for exc in task.exceptions if exc.type is ast.ExceptionType.FATAL
                and guard.get(f"{task.name}.{exc.name}") and f"{exc.name}.raised" in last.emitted)
    still = sorted(witness.model.active_tasks(last.target))
    return Violation(f"type-3 exception {name} gives status {last.status}"
                     + (f" with {', '.join(still)} still active" if still else ""), steps)


def _one_task_per_robot(model: SymbolicModel, witness: Witness) -> Violation | None:
    m = model.m
    by_robot: dict[str, list[int]] = {}
    for site in model.composition.sites:
        by_robot.setdefault(site.robot, []).append(site.number)
    clash = m.false
    for sites in by_robot.values():
        for i, a in enumerate(sites):
            for b in sites[i + 1:]:
                clash |= model.site_active_next[a] & model.site_active_next[b]
    run = shortest_run(model, clash)
    if run is None:
        return None
    steps = _steps(witness, run)
    robot = {s.number: (s.robot, s.task) for s in model.composition.sites}
    seen: dict[str, str] = {}
    for site in sorted(witness.model.sites(steps[-1].target)):
        name, task = robot[site]
        if name in seen:
            return Violation(f"{seen[name]} and {task} are active at once on robot {name}",
                             steps)
        seen[name] = task
    raise AssertionError("the symbolic clash is not in the explicit step")  # pragma: no cover


def _no_deadlock(model: SymbolicModel, witness: Witness) -> Violation | None:
    m = model.m
    composition = model.composition
    prep = model.circuit.prep
    spans = _endless_spans(composition.mission, composition.program)

    def endless(loc) -> bool:
        return any(contains(span, loc) for span in spans)

    good = model.term
    for pid, pause in enumerate(prep.pauses):
        if endless(pause.src.loc):
            good |= m.var(f"r{pid}")
    for site in composition.sites:
        if endless(site.loc):
            good |= model.site_active[site.number]
    reach = model.reachable
    can_end = good & reach
    while True:
        more = can_end | (model.preimage(can_end) & reach)
        if more == can_end:
            break
        can_end = more
    stuck = reach & ~can_end
    if stuck == m.false:
        return None
    bottom = _bottom_component(model, stuck)
    if (model.init & bottom) != m.false:
        steps: tuple[Step, ...] = ()
        where_key = witness.key(pick_state(model, model.init))
    else:
        run = shortest_run(model, model.compose(bottom))
        assert run is not None
        steps = _steps(witness, run)
        where_key = witness.automaton.keys[witness.model.control(steps[-1].target)]
    where = ", ".join(str(loc) for loc in _waiting(prep, where_key)) or "its start"
    return Violation(f"the mission can get stuck waiting at {where}: no end is reachable "
                     "from there and no loop or halt is meant to run forever", steps)


def _waiting(prep, key) -> tuple:
    if key is None or not isinstance(key, tuple) or key == ("terminated",):
        return ()
    return tuple(prep.pauses[pid].src.loc for pid in key if pid < prep.pre_base)


def _bottom_component(model: SymbolicModel, stuck: Node) -> Node:
    """A bottom strongly connected component inside ``stuck`` (closed under steps)."""
    m = model.m
    state = m.cube(pick_state(model, stuck))
    while True:
        forward = state
        while True:
            more = forward | (model.image(forward) & stuck)
            if more == forward:
                break
            forward = more
        backward = state
        while True:
            more = backward | (model.preimage(backward) & forward)
            if more == backward:
                break
            backward = more
        outside = forward & ~backward
        if outside == m.false:
            return forward
        state = m.cube(pick_state(model, outside))


def _tasks_end_first(model: SymbolicModel, witness: Witness) -> Violation | None:
    allowed = frozenset(s.number for s in model.composition.sites if s.on_fatal)
    everyone = _sites_outside(model, frozenset())
    ends = (model.status(Status.DONE) | model.status(Status.FAILED) | model.status("ended"))
    bad = (ends & everyone) | (model.status(Status.ABORTED) & _sites_outside(model, allowed))
    run = shortest_run(model, bad)
    if run is None:
        return None
    steps = _steps(witness, run)
    last = steps[-1]
    still = ", ".join(sorted(witness.model.active_tasks(last.target)))
    return Violation(f"the mission ends ({last.status}) with {still} still active", steps)


_CHECKS = {"fatal-aborts": _fatal_aborts, "one-task-per-robot": _one_task_per_robot,
           "no-deadlock": _no_deadlock, "tasks-end-first": _tasks_end_first}


def check_builtin_symbolic(model: SymbolicModel, witness: Witness, name: str
                           ) -> Violation | None:
    """None when built-in property ``name`` holds on the symbolic model, else the violation."""
    return _CHECKS[name](model, witness)
