"""Fixtures for executive tests: a producer/consumer pair and event-log filters."""

from __future__ import annotations

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


# the mission fixtures (tests/mission/conftest.py), for the executive tests that run a plan
from tests.mission.conftest import hold_task, plan_text  # noqa: E402,F401
