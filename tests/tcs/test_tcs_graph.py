"""TCS construction and coherence checks: each error names the bad value."""

from __future__ import annotations

import pytest

from orccad_app.diagnostics import OrccadError, SourceLocation
from orccad_app.tcs import TCS, ModuleTask, PhysicalResource, Port, Protocol, ms


def _tcs():
    tcs = TCS("rt")
    tcs.add(ModuleTask("traj", ms(10), ms(1), None, (Port("qd", "out", dim=3),)))
    tcs.add(ModuleTask("ctrl", ms(2), ms(1), None,
                       (Port("qd", "in", dim=3), Port("q", "in", dim=3), Port("tau", "out", dim=3),
                        Port("alarm", "out", "event"))))
    tcs.add(PhysicalResource("arm", (PhysicalResource.sensor("q", 3),
                                     PhysicalResource.actuator("tau", 3))))
    return tcs


def test_a_coherent_tcs_builds_its_graph():
    tcs = _tcs()
    tcs.connect("traj.qd", "ctrl.qd", "asyn/syn")
    tcs.connect("arm.q", "ctrl.q")
    tcs.connect("ctrl.tau", "arm.tau")
    tcs.check()
    graph = tcs.graph()
    assert set(graph.nodes) == {"traj", "ctrl", "arm"}
    assert graph.number_of_edges() == 3
    edge = graph.edges["traj", "ctrl", "ctrl.qd"]["connection"]
    assert edge.protocol is Protocol.ASYN_SYN
    assert [t.name for t in tcs.module_tasks] == ["traj", "ctrl"]
    assert tcs.feeding("ctrl.q").producer == "arm.q"


@pytest.mark.parametrize("producer, consumer, protocol, message", [
    ("trajx.qd", "ctrl.qd", "asyn/asyn", "unknown module 'trajx'"),
    ("traj.qdd", "ctrl.qd", "asyn/asyn", "unknown port 'traj.qdd'"),
    ("ctrl.qd", "traj.qd", "asyn/asyn", "'ctrl.qd' is an input port"),
    ("traj.qd", "ctrl.tau", "asyn/asyn", "'ctrl.tau' is an output port"),
    ("arm.q", "ctrl.qd", "asyn/asyn", None),  # fine: used to test the double feed below
    ("traj.qd", "ctrl.qd", "asyn/sync", "unknown protocol 'asyn/sync'"),
    ("traj", "ctrl.qd", "asyn/asyn", "bad port reference 'traj'"),
])
def test_bad_connections_are_rejected_naming_the_value(producer, consumer, protocol, message):
    tcs = _tcs()
    if message is None:
        tcs.connect(producer, consumer, protocol)
        with pytest.raises(OrccadError, match="input port 'ctrl.qd' is fed twice"):
            tcs.connect("traj.qd", "ctrl.qd")
        return
    with pytest.raises(OrccadError, match=message):
        tcs.connect(producer, consumer, protocol)


def test_type_and_dimension_must_agree():
    tcs = _tcs()
    tcs.add(ModuleTask("scalar", ms(5), ms(1), None, (Port("v", "out", dim=1),)))
    with pytest.raises(OrccadError, match=r"'scalar.v' is float\[1\] but 'ctrl.qd' is "
                                          r"float\[3\]"):
        tcs.connect("scalar.v", "ctrl.qd")


def test_unconnected_inputs_are_reported_with_the_location():
    tcs = TCS("rt")
    where = SourceLocation("m.orc", 4, 2)
    tcs.add(ModuleTask("ctrl", ms(2), ms(1), None, (Port("q", "in"),), location=where))
    with pytest.raises(OrccadError, match="input port 'ctrl.q' is not connected") as caught:
        tcs.check()
    assert caught.value.location == where


def test_connection_errors_carry_the_given_location():
    where = SourceLocation("m.orc", 9, 5)
    with pytest.raises(OrccadError) as caught:
        _tcs().connect("traj.qd", "ctrl.nope", location=where)
    assert caught.value.location == where


def test_module_task_attributes_are_validated():
    with pytest.raises(OrccadError, match="period_ns must be an integer"):
        ModuleTask("t", 0, 1)
    with pytest.raises(OrccadError, match="bcet_ns 5 exceeds wcet_ns 3"):
        ModuleTask("t", 10, 3, bcet_ns=5)
    with pytest.raises(OrccadError, match="priority must be an integer >= 1"):
        ModuleTask("t", 10, 3, priority=0)
    with pytest.raises(OrccadError, match="duplicate port name 'x'"):
        ModuleTask("t", 10, 3, None, (Port("x", "in"), Port("x", "out")))
    with pytest.raises(OrccadError, match="has no compute"):
        ModuleTask("t", 10, 3, object())
    with pytest.raises(OrccadError, match="direction must be 'in' or 'out'"):
        Port("x", "sideways")
    with pytest.raises(OrccadError, match="duplicate module name 'traj'"):
        _tcs().add(ModuleTask("traj", 10, 1))
    assert ModuleTask("t", 10, 3).deadline_ns == 10


def test_port_initial_values():
    assert Port("x", "in").initial_value() == 0.0
    assert list(Port("x", "in", dim=2).initial_value()) == [0.0, 0.0]
    assert Port("e", "in", "event").initial_value() is None
    assert Port("x", "in", initial=4.0).initial_value() == 4.0
