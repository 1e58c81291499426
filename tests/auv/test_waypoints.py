"""missions/auv_waypoints.orc end to end: the AUV visits the waypoints it receives as valued
inputs (``run GoTo(target = ?Waypoint)``, a run-time argument), holds station between them and
surfaces on Home; a waypoint the Robot-Task refuses ends the run ``failed`` at the argument."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from orccad_app.cli import main
from orccad_app.mission.injection import parse_injection
from orccad_app.mission.plan import plan_mission
from orccad_app.mission.run import MissionRun
from orccad_app.pipeline import load, select_mission

ROOT = Path(__file__).resolve().parents[2]
MISSION = ROOT / "missions" / "auv_waypoints.orc"
TOUR = ("Waypoint([15, 0, 5])@1", "Waypoint([15, 12, 8])@40", "Waypoint([0, 12, 5])@80",
        "Home@120")


@pytest.fixture(scope="module")
def plan():
    source = load(str(MISSION))
    return plan_mission(source, select_mission(source, None))


class _Where:
    """The vehicle's true position when each Robot-Task ends."""

    def __init__(self) -> None:
        self.run: MissionRun | None = None
        self.ends: list[tuple[str, np.ndarray]] = []

    def on_task_end(self, t_ns: int, task: str, site: int, outcome: str) -> None:
        vehicle = self.run.sim.plants["auv"].extension
        self.ends.append((task, np.asarray(vehicle.true_value("position"), dtype=float)))


def _tour(plan, *injections: str):
    where = _Where()
    run = MissionRun(plan, until_ns=300_000_000_000, observers=[where],
                     injections=[parse_injection(text) for text in injections])
    where.run = run
    return run.run(), where.ends


def test_the_vehicle_reaches_each_waypoint_it_receives(plan):
    result, ends = _tour(plan, *TOUR)
    assert (result.status, result.reason) == ("done", None)
    targets = [[15.0, 0.0, 5.0], [15.0, 12.0, 8.0], [0.0, 12.0, 5.0]]
    assert [(r.name, r.args, r.outcome) for r in result.robot_tasks] == [
        (name, {"target": target}, outcome) for target in targets
        for name, outcome in (("GoTo", "good_end"), ("Hold", "killed"))] + [
        ("Surface", {}, "good_end")]
    reached = [position for task, position in ends if task == "GoTo"]
    for position, target in zip(reached, targets):
        assert math.dist(position[:2], target[:2]) < 2.0  # within the post-condition's 1.5 m
        assert abs(position[2] - target[2]) < 1.5
    held = [position for task, position in ends if task == "Hold"]
    for position, target in zip(held, targets):  # station kept until the next waypoint
        assert math.dist(position[:2], target[:2]) < 2.0 and abs(position[2] - target[2]) < 1.0
    assert [(name, value) for _, name, value in result.outputs] == [
        ("Reached", 1), ("Reached", 2), ("Reached", 3)]
    assert ends[-1][0] == "Surface" and ends[-1][1][2] < 0.5


@pytest.mark.parametrize("waypoint, why", [
    ("[15, 0, -5]", "target = [15, 0, -5] is refused when the task starts: waypoint_guidance: "
                    "the depth of target must be >= 0 m, got [15.0, 0.0, -5.0]"),
    ("[15, 0]", "target = [15, 0] is refused when the task starts: a vector of 3 components is "
                "expected (the size of the default of 'target'), got 2: [15, 0]"),
])
def test_a_refused_waypoint_ends_the_run_failed_at_the_argument(plan, waypoint, why):
    result, _ = _tour(plan, f"Waypoint({waypoint})@1")
    assert result.status == "failed"
    assert result.reason == f"{MISSION}:72:30: run-time argument of GoTo: {why}"
    assert result.robot_tasks == [] and result.sim_time_ns == 1_000_000_000


def test_the_documented_react_script_walks_the_tour(capsys):
    status = main(["react", str(MISSION), "--inputs", str(ROOT / "missions/auv_waypoints.in")])
    out = capsys.readouterr().out.splitlines()
    assert status == 0
    assert "GoTo.start GoTo.arg.target([15.0, 0.0, 5.0])" in out[1]
    assert "Reached(1) Hold.start Hold.arg.target([15.0, 0.0, 5.0])" in out[2]
    assert "GoTo.start GoTo.arg.target([15.0, 12.0, 8.0])" in out[3]
    assert out[-1].endswith("[done]")


def test_a_constant_waypoint_of_the_wrong_size_is_a_compile_error(tmp_path, capsys):
    text = MISSION.read_text().replace("run GoTo(target = ?Waypoint) within 120 s;",
                                       "run GoTo(target = [15.0, 0.0]) within 120 s;")
    path = tmp_path / "w.orc"
    path.write_text(text)
    assert main(["compile", str(path)]) == 2
    err = capsys.readouterr().err
    assert f"{path}:72:21: error: waypoint_guidance: target must be [x, y, depth] (3 " \
           "components), got 2: [15.0, 0.0] (with the arguments of this run of GoTo)" in err
