"""Exception signals through the bus (RR-1801 §3.2.1: "exception signals must be sent using
safe protocols"): an observer on another processor than its Robot-Task's automaton sends its
signal as a bus message of class ``event``; the reaction then takes its declared execution
time on the automaton's processor. The bus reports its queueing per message class."""

from __future__ import annotations

import json

import pytest

from orccad_app.diagnostics import OrccadError
from orccad_app.executive import Bus, EventLog, Processor, Simulation
from orccad_app.mission.run import MissionRun
from orccad_app.tcs import TCS, ModuleTask, Port, ms, us
from orccad_app.trace.report import format_report, report_dict

TASK = """
robot arm : arm3dof;

robottask Track() on arm {
    duration 1 s;
    task_function joint_tracking(trajectory = cosine(q0 = [0.5, 0.5, 0.5], omega = pi));
    law pid(kp = 400.0, kv = 40.0, ki = 10.0);
    %s
    module traj  : trajectory  period 1 ms wcet 0.1 ms on cpu0 priority 2;
    module ctrl  : control_law period 1 ms wcet 0.3 ms on cpu0 priority 1;
    module watch : tracking_error(max = 0.02) period 1 ms wcet 0.05 ms on %s priority 3;
    connect traj.qd     -> ctrl.qd;
    connect traj.qd_dot -> ctrl.qd_dot;
    connect arm.q       -> ctrl.q;
    connect arm.qdot    -> ctrl.qdot;
    connect ctrl.tau    -> arm.tau;
    connect ctrl.e      -> watch.e;
    exception TrackingLost from watch : abort;
}
mission M { output Lost; try { run Track(); } catch TrackingLost { emit Lost; } }
"""
TRANSFER_NS = us(100)
REACTION = "automaton on cpu0 reaction 0.05 ms;"


def _abort(plan_text, observer_cpu: str, automaton: str = REACTION):
    log = EventLog()
    plan = plan_text(TASK % (automaton, observer_cpu))
    result = MissionRun(plan, bus=Bus(transfer_ns=TRANSFER_NS), observers=[log]).run()
    assert result.status == "done" and result.exceptions[0].name == "TrackingLost"
    sent = next(e[1] for e in log.events
                if e[0] == "on_signal" and e[2] == "Track.watch.event")
    return result, log, sent, result.exceptions[0].time_ns - sent


def test_an_observer_on_another_processor_delays_the_abort_by_the_bus_transfer(plan_text):
    _, local_log, _, local_delay = _abort(plan_text, "cpu0")
    result, log, sent, remote_delay = _abort(plan_text, "cpu1")
    assert local_delay == us(50)                       # the reaction time alone
    events = [e for e in log.events if e[0] == "on_message" and e[3] == "event"]
    assert len(events) == 1 and events[0][4] == "Track.watch.event -> automaton@cpu0"
    delivered, queued = events[0][1], events[0][5]
    assert queued == 0 and delivered == sent + TRANSFER_NS  # send, then delivery
    assert remote_delay == us(50) + TRANSFER_NS        # the abort comes 0.1 ms later
    assert remote_delay - local_delay == TRANSFER_NS
    assert not [e for e in local_log.events if e[0] == "on_message" and e[3] == "event"]
    # the reaction ran as a job on cpu0 (priority above every Module-Task)
    assert ("on_start", sent + TRANSFER_NS, "automaton@cpu0", 0, "cpu0") in log.events
    assert result.stats.reactions["automaton@cpu0"].completed == 1


def test_without_a_declaration_the_automaton_is_on_the_first_processor(plan_text):
    result, log, _, delay = _abort(plan_text, "cpu1", automaton="")
    assert delay == TRANSFER_NS                        # a zero-time reaction, after the bus
    assert result.stats.bus.by_kind["event"] == 1


def test_the_declaration_is_checked(plan_text):
    with pytest.raises(OrccadError, match="duplicate 'automaton'"):
        plan_text(TASK % (REACTION + "\n    " + REACTION, "cpu0"))


def test_bus_queueing_is_reported_per_message_class():
    # P (cpu0) writes three ports to C (cpu1) every 1 ms; a signal sent in the same instant
    # queues behind the three data messages
    tcs = TCS("q")
    tcs.add(ModuleTask("P", ms(1), us(10), _Writer(), tuple(Port(f"y{i}", "out")
                                                             for i in range(3))))
    tcs.add(ModuleTask("C", ms(1), us(10), None, tuple(Port(f"u{i}", "in") for i in range(3)),
                       processor="cpu1"))
    for i in range(3):
        tcs.connect(f"P.y{i}", f"C.u{i}", "asyn/asyn")
    log = EventLog()
    sim = Simulation(tcs, bus=Bus(transfer_ns=TRANSFER_NS), observers=[log],
                     processors=[Processor("cpu0"), Processor("cpu1")])
    got = []
    server = sim.reaction_server("cpu0", 0, got.extend)
    sim.signal_routes.add("C.alarm", "cpu1", server)
    sim.activate()
    sim.at(us(10), lambda s: s.signal_routes.send("C.alarm", True))  # just after P's writes
    stats = sim.run(ms(2))
    classes = stats.bus.by_class()
    assert classes["event"] == {"messages": 1, "queued_mean_ns": 3 * TRANSFER_NS,
                                "queued_max_ns": 3 * TRANSFER_NS}
    assert classes["port_data"]["messages"] == 6
    assert classes["port_data"]["queued_max_ns"] == 2 * TRANSFER_NS
    assert got == [("C.alarm", True)]
    assert ("on_message", us(410), "bus", "event", "C.alarm -> automaton@cpu0",
            3 * TRANSFER_NS) in log.events


def test_the_run_report_gives_queueing_per_class(plan_text):
    result, _, _, _ = _abort(plan_text, "cpu1")
    report = report_dict(result)
    json.dumps(report, allow_nan=False)
    assert report["bus"]["classes"]["event"]["messages"] == 1
    assert report["bus"]["classes"]["port_data"]["messages"] == result.stats.bus.messages - 1
    assert report["reactions"]["automaton@cpu0"]["count"] == 1
    text = format_report(result)
    assert "event signals: 1 messages, queueing mean 0.000 ms" in text
    assert "Reactions on cpu0: 1, longest 0.050 ms" in text


class _Writer:
    def compute(self, t_s, inputs):
        return {"y0": 0, "y1": 1, "y2": 2}
