"""Sporadic (interrupt-driven) Module-Tasks: released by their inputs' writes or by
interrupts, never more often than their minimum inter-arrival time; early interrupts are
deferred (or coalesced into a release already due) and counted."""

from __future__ import annotations

import pytest

from orccad_app.diagnostics import OrccadError
from orccad_app.executive import Bus, EventLog, Processor, Simulation
from orccad_app.mission.run import MissionRun
from orccad_app.tcs import TCS, ModuleTask, Port, ms, us
from orccad_app.tcs.phasing import Activation


def _pair(counter, recorder, *, producer_ms=1.0, min_ms=2.5, remote=False, protocol="asyn/asyn",
          bus=None):
    tcs = TCS("pair")
    tcs.add(ModuleTask("P", ms(producer_ms), us(100), counter(), (Port("y", "out"),),
                       priority=1))
    consumer = recorder()
    tcs.add(ModuleTask("S", ms(min_ms), us(200), consumer, (Port("u", "in"),), priority=2,
                       processor="cpu1" if remote else "cpu0",
                       activation=Activation.SPORADIC))
    tcs.connect("P.y", "S.u", protocol)
    log = EventLog()
    sim = Simulation(tcs, observers=[log], bus=bus,
                     processors=[Processor("cpu0"), Processor("cpu1")])
    return sim, consumer, log


def _releases(log, module="S"):
    return [e[1] for e in log.events if e[0] == "on_release" and e[2] == module]


def test_writes_release_it_never_faster_than_the_minimum(counter, recorder):
    sim, consumer, log = _pair(counter, recorder)
    sim.activate()
    stats = sim.run(ms(10))
    # P writes at 0.1, 1.1, 2.1 ... ms; S is released at the first write, then every 2.5 ms
    assert _releases(log) == [us(100), us(2600), us(5100), us(7600)]
    # and reads the value written just before its release (not a stale one)
    assert [inputs["u"] for _, inputs in consumer.seen] == [1, 3, 6, 8]
    sporadic = stats.sporadic["S"]
    assert sporadic.interrupts == 10 and sporadic.released == 4
    assert sporadic.deferred == 4 and sporadic.coalesced == 5
    assert sporadic.min_gap_ns == ms(2.5)


def test_an_interrupt_after_the_minimum_releases_at_once(counter, recorder):
    sim, _, log = _pair(counter, recorder, producer_ms=3.0)
    sim.activate()
    stats = sim.run(ms(10))
    assert _releases(log) == [us(100), us(3100), us(6100), us(9100)]
    assert stats.sporadic["S"].deferred == 0


def test_external_interrupts_and_refusals(counter, recorder):
    sim, _, log = _pair(counter, recorder, producer_ms=100.0)
    sim.activate()
    for t_ms in (20, 21, 21.5, 30):
        sim.interrupt("S", at_ns=ms(t_ms))
    stats = sim.run(ms(40))
    assert _releases(log) == [us(100), ms(20), ms(22.5), ms(30)]
    assert stats.sporadic["S"].deferred == 1 and stats.sporadic["S"].coalesced == 1
    with pytest.raises(OrccadError, match="'P' is periodic"):
        sim.interrupt("P")
    with pytest.raises(OrccadError, match="unknown module-task 'Q'"):
        sim.interrupt("Q")


def test_inactive_and_killed_ones_are_not_released(counter, recorder):
    sim, _, log = _pair(counter, recorder)
    sim.activate("P")
    sim.run(ms(5))
    assert _releases(log) == []
    sim.activate("S")
    sim.run(ms(6))               # released by P's write at 5.1 ms
    sim.kill("S", at_ns=ms(7))   # its release due at 7.6 ms is withdrawn
    sim.run(ms(10))
    assert _releases(log) == [us(5100)]
    sim.activate("S")            # starts afresh: no minimum to wait
    sim.run(ms(11))
    assert _releases(log) == [us(5100), us(10100)]


def test_across_the_bus_the_delivery_is_the_interrupt(counter, recorder):
    sim, consumer, log = _pair(counter, recorder, remote=True, bus=Bus(transfer_ns=us(50)))
    sim.activate()
    sim.run(ms(3))
    assert _releases(log) == [us(150), us(2650)]
    assert [inputs["u"] for _, inputs in consumer.seen] == [1, 3]


def test_a_pull_protocol_across_the_bus_does_not_interrupt(counter, recorder):
    sim, _, log = _pair(counter, recorder, remote=True, protocol="asyn/synD",
                        bus=Bus(transfer_ns=us(50)))
    sim.activate()
    sim.interrupt("S", at_ns=ms(1))
    sim.run(ms(5))
    assert _releases(log) == [ms(1)]


SPORADIC_TASK = """
robot arm : arm3dof;

robottask Hold(kp: float = 400.0) on arm {
    duration 0.2 s;
    task_function joint_tracking(trajectory = constant(value = [0.0, 0.0, 0.0]));
    law pid(kp = kp, kv = 40.0);
    module traj : trajectory  period 1 ms wcet 0.1 ms on cpu0 priority 2;
    module ctrl : control_law period 1 ms wcet 0.3 ms on cpu0 priority 1;
    module te   : tracking_error(max = 0.2) %s wcet 0.05 ms on %s priority 3;
    connect traj.qd     -> ctrl.qd;
    connect traj.qd_dot -> ctrl.qd_dot;
    connect arm.q       -> ctrl.q;
    connect arm.qdot    -> ctrl.qdot;
    connect ctrl.tau    -> arm.tau;
    connect %s -> te.e;
    exception TrackingLost from te : abort;
}
mission M { run Hold(); }
"""


def test_the_language_declares_a_sporadic_observer(plan_text):
    plan = plan_text(SPORADIC_TASK % ("sporadic min_interarrival 2 ms", "cpu0", "ctrl.e"))
    te = plan.tcs.module("Hold.te")
    assert te.activation is Activation.SPORADIC and te.period_ns == ms(2)
    result = MissionRun(plan).run()
    assert result.status == "done"
    stats = result.stats.sporadic["Hold.te"]
    assert stats.released == 100 and stats.min_gap_ns == ms(2)   # 0.2 s at most every 2 ms
    # ctrl writes e in 199 jobs (its first has no reference yet): one release at once, 99
    # deferred to the end of the minimum, 99 coalesced into a release already due
    assert stats.interrupts == 199 and stats.deferred == 99 and stats.coalesced == 99


@pytest.mark.parametrize("clause,cpu,source,message", [
    ("period 5 ms sporadic min_interarrival 2 ms", "cpu0", "ctrl.e", "not both"),
    ("sporadic min_interarrival 2 ms", "cpu0", "arm.q", "no input whose writes can release"),
    ("sporadic min_interarrival 2 ms sporadic min_interarrival 3 ms", "cpu0", "ctrl.e",
     "duplicate 'min_interarrival'"),
])
def test_sporadic_declarations_that_cannot_work_are_refused(plan_text, clause, cpu, source,
                                                            message):
    text = SPORADIC_TASK % (clause, cpu, source)
    if source == "arm.q":
        text = text.replace("tracking_error(max = 0.2)", "joint_limits(margin = 0.05)") \
            .replace("-> te.e", "-> te.q")
    with pytest.raises(OrccadError, match=message):
        plan_text(text)
