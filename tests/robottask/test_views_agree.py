"""The abstract view (``orccad react``) and the composed view (``run``, ``react --composed``)
agree on every observable a mission can wait for (issue 28, 1).

The composed automaton is driven by random observer events and clock steps; each instant is
replayed on the abstract automaton with the outcomes the composed one produced (``X.good_end``
when it emitted it, ``X.E`` when it raised ``E`` from task ``X``); both must then emit the same
mission-level outputs (every output but the RTA's internal ``X.good_end``, ``X.measure``,
``X.activate``, ``X.E.adjust``) and have the same status and reason, instant by instant. The
defect: the abstract view never emitted a Robot-Task's ``postcondition emit S``.
"""

from __future__ import annotations

import random
from pathlib import Path

import pytest

from orccad_app.pipeline import ABSTRACT, COMPOSED, compile_mission, load, select_mission
from orccad_app.reactive.runtime import Reactor, RelationViolation

ROOT = Path(__file__).resolve().parents[2]
SHIPPED = sorted((ROOT / "missions").glob("*.orc"))

SYNC = """
robot arm : arm3dof;
robot arm2 : arm3dof;

robottask First(g : vector) on arm {
    task_function joint_tracking(trajectory = min_jerk(goal = g, duration = 1.0));
    law pid(kp = 400.0, kv = 40.0);
    module traj : trajectory period 1 ms wcet 0.1 ms;
    module ctrl : control_law period 1 ms wcet 0.3 ms;
    connect traj.qd -> ctrl.qd : asyn/asyn;
    connect traj.qd_dot -> ctrl.qd_dot : asyn/asyn;
    connect arm.q -> ctrl.q : asyn/asyn;
    connect arm.qdot -> ctrl.qdot : asyn/asyn;
    connect ctrl.tau -> arm.tau : asyn/asyn;
    postcondition measure at_goal(tol = 0.01);
    postcondition emit Placed;
}

robottask Second(g : vector) on arm2 {
    task_function joint_tracking(trajectory = min_jerk(goal = g, duration = 1.0));
    law pid(kp = 400.0, kv = 40.0);
    module traj : trajectory period 1 ms wcet 0.1 ms;
    module ctrl : control_law period 1 ms wcet 0.3 ms;
    connect traj.qd -> ctrl.qd : asyn/asyn;
    connect traj.qd_dot -> ctrl.qd_dot : asyn/asyn;
    connect arm2.q -> ctrl.q : asyn/asyn;
    connect arm2.qdot -> ctrl.qdot : asyn/asyn;
    connect ctrl.tau -> arm2.tau : asyn/asyn;
    precondition Placed;
    postcondition measure at_goal(tol = 0.01);
    postcondition emit Handed;
}

mission Sync {
    output Placed, Handed, Done;
    par { run First(g = [0.1, 0.1, 0.1]); } || { run Second(g = [0.2, 0.2, 0.2]); }
        || { await Handed; }
    emit Done;
}
"""

_INTERNAL = ("good_end", "measure", "activate")


def _missions() -> list[tuple[str, str]]:
    found = []
    for path in SHIPPED:
        source = load(path)
        for mission in source.program.missions:
            found.append((str(path), mission.name))
    return found


def _observable(outputs: tuple[str, ...], tasks: set[str]) -> set[str]:
    kept = set()
    for name in outputs:
        head, _, tail = name.partition(".")
        if head in tasks and (tail in _INTERNAL or tail.endswith(".adjust")):
            continue
        kept.add(name)
    return kept


def _compare(path: str, mission_name: str, text: str | None, seed: int, steps: int) -> None:
    source = load(path, text=text)
    mission = select_mission(source, mission_name)
    composed = compile_mission(source, mission, view=COMPOSED, lazy=True)
    abstract = compile_mission(source, mission, view=ABSTRACT, lazy=True)
    tasks = {t.name for t in source.program.robottasks}
    pure = [s.name for s in composed.inputs if s.type is None]
    abstract_inputs = {s.name for s in abstract.inputs}
    ours = {s.name for s in abstract.inputs if s.type is None and "." not in s.name}
    rng = random.Random(seed)
    left, right = Reactor(composed), Reactor(abstract)
    clock = 0
    active: set[str] = set()
    for instant in range(steps):
        clock += rng.choice((0, 1_000_000, 20_000_000, 200_000_000, 1_000_000_000))
        wanted = {name for name in pure if rng.random() < 0.12}
        try:
            got = left.react(wanted, clock)
        except RelationViolation:
            wanted = set()
            got = left.react(wanted, clock)
        outcome = {name for name in wanted if name in ours}
        for name in got.outputs:
            head, _, tail = name.partition(".")
            if head in tasks and tail == "good_end":
                outcome.add(name)
            elif name.endswith(".raised"):
                exception = name[:-len(".raised")]
                raisers = {f"{x}.{exception}" for x in active} & abstract_inputs
                fed = {f"{x}.{exception}" for x in tasks} & wanted & abstract_inputs
                outcome |= fed or raisers
        mine = right.react(outcome, clock)
        for name in mine.outputs:
            head, _, tail = name.partition(".")
            if tail == "start":
                active.add(head)
        where = f"{Path(path).name} -m {mission_name}, seed {seed}, instant {instant + 1}"
        assert _observable(got.outputs, tasks) == _observable(mine.outputs, tasks), \
            f"{where}: composed {sorted(got.outputs)} with {sorted(wanted)}, abstract " \
            f"{sorted(mine.outputs)} with {sorted(outcome)}"
        assert (got.status, got.reason) == (mine.status, mine.reason), where
        if left.finished:
            break


@pytest.mark.parametrize("path, mission", _missions(),
                         ids=[f"{Path(p).stem}-{m}" for p, m in _missions()])
def test_abstract_and_composed_views_agree_on_every_shipped_mission(path, mission):
    for seed in range(4):
        _compare(path, mission, None, seed, 150)


def test_a_postcondition_emit_is_emitted_in_the_abstract_view_too(tmp_path):
    path = tmp_path / "sync.orc"
    path.write_text(SYNC, encoding="utf-8")
    for seed in range(8):
        _compare(str(path), "Sync", None, seed, 120)
    # and directly: First ends, Placed starts Second, Second ends, Handed ends the mission
    source = load(path)
    reactor = Reactor(compile_mission(source, select_mission(source, "Sync"), view=ABSTRACT,
                                      lazy=True))
    assert set(reactor.react(set()).outputs) == {"First.start", "Second.start"}
    assert set(reactor.react({"First.good_end"}).outputs) == {"Placed"}
    final = reactor.react({"Second.good_end"})
    assert set(final.outputs) == {"Handed", "Done"} and final.status == "done"
