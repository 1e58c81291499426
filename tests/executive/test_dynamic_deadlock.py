"""Dynamic deadlock detection: Module-Tasks blocked on each other stop the run."""

from __future__ import annotations

import pytest

from orccad_app.diagnostics import OrccadError
from orccad_app.executive import DeadlockError, EventLog, Processor, Simulation
from orccad_app.tcs import TCS, ModuleTask, Port, ms


class Echo:
    def compute(self, t_s, inputs):
        return {"y": 1.0}


def _module(name, period_ms, processor="cpu0", priority=1):
    return ModuleTask(name, ms(period_ms), ms(1), Echo(), (Port("x", "in"), Port("y", "out")),
                      processor=processor, priority=priority)


def test_two_modules_reading_each_other_synchronously_deadlock_at_once():
    tcs = TCS("loop", [_module("a", 10), _module("b", 10, priority=2)])
    tcs.connect("a.y", "b.x", "asyn/syn")
    tcs.connect("b.y", "a.x", "asyn/syn")
    log = EventLog()
    sim = Simulation(tcs, observers=[log])
    sim.activate()
    with pytest.raises(DeadlockError) as caught:
        sim.run(ms(100))
    error = caught.value
    assert isinstance(error, OrccadError)
    assert set(error.cycle) == {"a.x", "b.x"}
    assert error.time_ns == 0
    assert "a.x (read, asyn/syn) waits for b" in error.message
    assert "b.x (read, asyn/syn) waits for a" in error.message
    assert log.events[-1][0] == "on_deadlock"
    assert sim.now_ns == 0


def test_a_three_module_cycle_found_later_names_every_port():
    # a -> b -> c -> a; c's input is a rendez-vous with a, the others wait for fresh data.
    tcs = TCS("ring", [_module("a", 10, "p0"), _module("b", 10, "p1"), _module("c", 10, "p2")])
    tcs.connect("a.y", "b.x", "asyn/synF")
    tcs.connect("b.y", "c.x", "asyn/synF")
    tcs.connect("c.y", "a.x", "asyn/synF")
    sim = Simulation(tcs)
    sim.activate()
    with pytest.raises(DeadlockError) as caught:
        sim.run(ms(100))
    assert sorted(caught.value.cycle) == ["a.x", "b.x", "c.x"]


def test_a_rendez_vous_pair_runs_without_deadlock():
    tcs = TCS("rdv")
    tcs.add(ModuleTask("p", ms(5), ms(1), Echo(), (Port("y", "out"),)))
    tcs.add(ModuleTask("c", ms(5), ms(1), None, (Port("x", "in"),), processor="cpu1"))
    tcs.connect("p.y", "c.x", "syn/syn")
    sim = Simulation(tcs, processors=[Processor("cpu0"), Processor("cpu1")])
    sim.activate()
    stats = sim.run(ms(100))
    assert stats.tasks["c"].completed == 20


def test_waiting_on_a_killed_module_is_not_reported_as_a_deadlock():
    tcs = TCS("orphan")
    tcs.add(ModuleTask("p", ms(5), ms(1), Echo(), (Port("y", "out"),)))
    tcs.add(ModuleTask("c", ms(5), ms(1), None, (Port("x", "in"),), processor="cpu1"))
    tcs.connect("p.y", "c.x", "asyn/synF")
    sim = Simulation(tcs)
    sim.activate("c")
    stats = sim.run(ms(50))
    assert stats.tasks["c"].completed == 0
    assert stats.tasks["c"].overruns == 9
    assert stats.tasks["c"].deadline_misses == 1
