"""Determinism: the same TCS, seed and commands give the same event log, bit for bit."""

from __future__ import annotations

from orccad_app.executive import Bus, EventLog, Processor, Simulation
from orccad_app.tcs import TCS, ModuleTask, Port, ms, us


class Noisy:
    """Writes a value drawn from its own generator: its output depends on the job count."""

    def __init__(self) -> None:
        self.k = 0

    def compute(self, t_s, inputs):
        self.k += 1
        return {"y": self.k * 0.5 + t_s}


class Sink:
    def compute(self, t_s, inputs):
        return {"alarm": inputs["u"] > 5}


def _log(seed: int) -> list[tuple]:
    tcs = TCS("det")
    tcs.add(ModuleTask("src", ms(2), us(900), Noisy(), (Port("y", "out"),), priority=1,
                       bcet_ns=us(100)))
    tcs.add(ModuleTask("mid", ms(3), us(800), Noisy(), (Port("y", "out"),), priority=2,
                       bcet_ns=us(200)))
    tcs.add(ModuleTask("sink", ms(5), us(700), Sink(),
                       (Port("u", "in"), Port("v", "in"), Port("alarm", "out", "event")),
                       priority=3, bcet_ns=us(300), processor="cpu1"))
    tcs.connect("src.y", "sink.u", "asyn/syn")
    tcs.connect("mid.y", "sink.v", "asyn/synDF")
    log = EventLog()
    sim = Simulation(tcs, seed=seed, observers=[log], bus=Bus(transfer_ns=us(150)),
                     processors=[Processor("cpu0", context_switch_ns=us(10)), Processor("cpu1")])
    sim.activate()
    sim.run(ms(200))
    return log.events


def test_same_seed_gives_an_identical_event_log():
    first = _log(seed=11)
    assert len(first) > 1000
    assert first == _log(seed=11)


def test_a_different_seed_changes_the_run_when_execution_times_are_random():
    assert _log(seed=11) != _log(seed=12)


def test_execution_times_are_drawn_within_bcet_and_wcet():
    tcs = TCS("draw", [ModuleTask("t", ms(1), us(500), bcet_ns=us(200))])
    log = EventLog()
    sim = Simulation(tcs, seed=3, observers=[log])
    sim.activate()
    stats = sim.run(ms(300))
    responses = [e[4] for e in log.events if e[0] == "on_finish"]
    assert min(responses) >= us(200) and max(responses) <= us(500)
    assert len(set(responses)) > 100
    assert stats.tasks["t"].response_min_ns == min(responses)
