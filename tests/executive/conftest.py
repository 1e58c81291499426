"""Fixtures for executive tests: a producer/consumer pair and event-log filters."""

from __future__ import annotations

import shutil

import pytest

from orccad_app.executive import Bus, EventLog, Processor, Simulation
from orccad_app.tcs import TCS, ModuleTask, Port, ms


class Counter:
    """Writes 1, 2, 3, ... on ``y``, one per job."""

    def __init__(self) -> None:
        self.count = 0

    def compute(self, t_s: float, inputs: dict) -> dict:
        self.count += 1
        return {"y": self.count}


class Recorder:
    """Records ``(t_s, inputs)`` per job and writes nothing."""

    def __init__(self) -> None:
        self.seen: list[tuple[float, dict]] = []

    def compute(self, t_s: float, inputs: dict) -> dict:
        self.seen.append((t_s, dict(inputs)))
        return {}


def _ms(t_ns: int) -> float:
    return t_ns / 1e6


class PairRun:
    """A finished run of producer ``P`` -> consumer ``C`` with its event log."""

    def __init__(self, sim: Simulation, log: EventLog) -> None:
        self.sim = sim
        self.log = log

    def blocks(self) -> list[tuple]:
        """``(t_ms, module, op)`` per block."""
        return [(_ms(e[1]), e[2], e[4]) for e in self.log.events if e[0] == "on_block"]

    def unblocks(self) -> list[tuple]:
        """``(t_ms, module, op, blocked_ms)`` per unblock."""
        return [(_ms(e[1]), e[2], e[4], _ms(e[5])) for e in self.log.events
                if e[0] == "on_unblock"]

    def reads(self) -> list[tuple]:
        """``(t_ms, value)`` per read of the consumer."""
        return [(_ms(e[1]), e[4]) for e in self.log.events if e[0] == "on_read"]


@pytest.fixture
def run_pair():
    """Run producer ``P`` (priority 2) -> consumer ``C`` (priority 1) under ``protocol``.

    Execution times are 1 ms; by default both share ``cpu0`` (``remote=True`` puts C on
    ``cpu1`` behind ``bus``).
    """

    def run(protocol: str, p_period_ms: float, c_period_ms: float, until_ms: float,
            remote: bool = False, bus: Bus | None = None) -> PairRun:
        tcs = TCS("pair")
        tcs.add(ModuleTask("P", ms(p_period_ms), ms(1), Counter(), (Port("y", "out"),),
                           priority=2))
        tcs.add(ModuleTask("C", ms(c_period_ms), ms(1), Recorder(), (Port("u", "in"),),
                           priority=1, processor="cpu1" if remote else "cpu0"))
        tcs.connect("P.y", "C.u", protocol)
        log = EventLog()
        sim = Simulation(tcs, observers=[log], bus=bus,
                         processors=[Processor("cpu0"), Processor("cpu1")])
        sim.activate()
        sim.run(ms(until_ms))
        return PairRun(sim, log)

    return run


@pytest.fixture
def counter():
    return Counter


@pytest.fixture
def recorder():
    return Recorder


# -- missions in the loop ----------------------------------------------------------------------

ROOT = __import__("pathlib").Path(__file__).resolve().parents[2]

HOLD_TASK = """
robot arm : arm3dof;

robottask Hold(kp: float = 400.0) on arm {
    duration 0.2 s;
    task_function joint_tracking(trajectory = constant(value = [0.0, 0.0, 0.0]));
    law pid(kp = kp, kv = 40.0);
    module traj : trajectory  period 1 ms wcet 0.1 ms on cpu0 priority 2;
    module ctrl : control_law period 1 ms wcet 0.3 ms on cpu0 priority 1;
    connect traj.qd     -> ctrl.qd;
    connect traj.qd_dot -> ctrl.qd_dot;
    connect arm.q       -> ctrl.q;
    connect arm.qdot    -> ctrl.qdot;
    connect ctrl.tau    -> arm.tau;
%s
}
"""
"""A Robot-Task holding the arm at 0 for 0.2 s; ``%s`` takes extra clauses."""


def _plan_text(tmp_path, text: str, mission: str | None = None):
    """The :class:`MissionPlan` of a plan written to a file under ``tmp_path``."""
    from orccad_app.mission.plan import plan_mission
    from orccad_app.pipeline import load, select_mission

    path = tmp_path / "mission.orc"
    path.write_text(text, encoding="utf-8")
    source = load(path)
    return plan_mission(source, select_mission(source, mission))


def _plan_file(path, replacements: dict[str, str] | None = None, tmp_path=None):
    """The plan of a mission file of the repository, optionally edited (text replaced)."""
    from orccad_app.mission.plan import plan_mission
    from orccad_app.pipeline import load, select_mission

    path = ROOT / path
    if replacements:
        text = path.read_text(encoding="utf-8")
        for old, new in replacements.items():
            assert old in text, old
            text = text.replace(old, new)
        if (path.parent / "lib").is_dir():  # the sub-missions it imports, beside the copy
            shutil.copytree(path.parent / "lib", tmp_path / "lib", dirs_exist_ok=True)
        return _plan_text(tmp_path, text)
    source = load(path)
    return plan_mission(source, select_mission(source, None))


@pytest.fixture(scope="session")
def pid_run():
    """One run of missions/arm_pid.orc (seed 0): ``(plan, result)``."""
    from orccad_app.mission.run import MissionRun

    plan = _plan_file("missions/arm_pid.orc")
    return plan, MissionRun(plan).run()


@pytest.fixture
def plan_text(tmp_path):
    """``plan_text(text, mission=None)``: the plan of a plan-language text."""
    return lambda text, mission=None: _plan_text(tmp_path, text, mission)


@pytest.fixture
def plan_file(tmp_path):
    """``plan_file(path, {old: new})``: the plan of a repository mission, text edited."""
    return lambda path, replacements=None: _plan_file(path, replacements, tmp_path)


@pytest.fixture
def hold_task():
    """The text of the ``Hold`` Robot-Task, ``%s`` for extra clauses."""
    return HOLD_TASK
