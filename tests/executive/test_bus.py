"""The bus: per-message transfer time, FIFO contention, statistics."""

from __future__ import annotations

from orccad_app.executive import Bus, EventLog, Processor, Simulation
from orccad_app.tcs import TCS, ModuleTask, Port, ms


class Source:
    def compute(self, t_s, inputs):
        return {"y": 1.0}


def test_simultaneous_writes_queue_in_fifo_order_and_contention_is_measured():
    tcs = TCS("bus")
    for i in range(3):
        tcs.add(ModuleTask(f"p{i}", ms(10), ms(1), Source(), (Port("y", "out"),),
                           processor=f"cpu{i}"))
    tcs.add(ModuleTask("c", ms(10), ms(1), None,
                       tuple(Port(f"u{i}", "in") for i in range(3)), processor="cpu3"))
    for i in range(3):
        tcs.connect(f"p{i}.y", f"c.u{i}", "asyn/asyn")
    log = EventLog()
    bus = Bus(transfer_ns=ms(2))
    sim = Simulation(tcs, bus=bus, observers=[log])
    sim.activate()
    sim.run(ms(10))
    # the three producers write at 1 ms; transfers end at 3, 5, 7 ms in write order.
    messages = [(e[1], e[4], e[5]) for e in log.events if e[0] == "on_message"]
    assert messages == [(ms(3), "p0.y -> c.u0 (asyn/asyn)", 0),
                        (ms(5), "p1.y -> c.u1 (asyn/asyn)", ms(2)),
                        (ms(7), "p2.y -> c.u2 (asyn/asyn)", ms(4))]
    assert bus.stats.messages == 3
    assert bus.stats.queued_ns == ms(6)
    assert bus.stats.max_queued_ns == ms(4)
    assert bus.stats.mean_queued_ns == ms(2)
    assert bus.stats.busy_ratio == 0.6


def test_value_becomes_visible_when_its_message_is_delivered():
    tcs = TCS("late")
    tcs.add(ModuleTask("p", ms(10), ms(1), Source(), (Port("y", "out"),), processor="a"))
    tcs.add(ModuleTask("c", ms(1), ms(0), None, (Port("u", "in"),), processor="b"))
    tcs.connect("p.y", "c.u")
    log = EventLog()
    sim = Simulation(tcs, bus=Bus(transfer_ns=ms(2)), observers=[log],
                     processors=[Processor("a"), Processor("b")])
    sim.activate()
    sim.run(ms(5))
    reads = [(e[1], e[4]) for e in log.events if e[0] == "on_read"]
    # written at 1 ms, delivered at 3 ms: the read at 2 ms still sees the initial value.
    assert reads == [(0, "0.0"), (ms(1), "0.0"), (ms(2), "0.0"), (ms(3), "1.0"),
                     (ms(4), "1.0")]


def test_busy_ratio_counts_a_transfer_in_progress_at_the_end():
    tcs = TCS("cut")
    tcs.add(ModuleTask("p", ms(10), ms(1), Source(), (Port("y", "out"),), processor="a"))
    tcs.add(ModuleTask("c", ms(10), ms(1), None, (Port("u", "in"),), processor="b"))
    tcs.connect("p.y", "c.u")
    bus = Bus(transfer_ns=ms(4))
    sim = Simulation(tcs, bus=bus)
    sim.activate()
    sim.run(ms(3))
    assert bus.stats.busy_ns == ms(2) and bus.stats.messages == 0
