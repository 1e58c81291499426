"""``orccad tcs``'s report: graph in text, DOT and JSON; verdicts."""

from __future__ import annotations

from orccad_app.tcs import TCS, ModuleTask, PhysicalResource, Port, ms
from orccad_app.tcs.report import analyse, to_dict, to_dot, to_text


def _tcs(protocol="asyn/asyn", wcet_b=ms(2)):
    tcs = TCS("Pair")
    tcs.add(PhysicalResource("arm", (PhysicalResource.sensor("q", 3),)))
    tcs.add(ModuleTask("a", ms(5), ms(1), ports=(Port("q", "in", dim=3), Port("y", "out"),
                                                 Port("u", "in")), priority=1, kind="law"))
    tcs.add(ModuleTask("b", ms(10), wcet_b, ports=(Port("x", "in"), Port("v", "out")),
                       priority=2, processor="cpu1"))
    tcs.connect("arm.q", "a.q")
    tcs.connect("a.y", "b.x", protocol)
    tcs.connect("b.v", "a.u", protocol)
    return tcs


def test_a_coherent_schedulable_tcs_is_ok():
    report = analyse(_tcs(), processors=2)
    assert report.ok and report.coherence is None and report.cycles == []
    text = to_text(report)
    assert "a                    prio  1  R =      1 ms  D =      5 ms  ok" in text
    assert "cpu1: utilization 0.200" in text
    assert "Deadlock analysis: no cycle of blocking protocols" in text
    data = to_dict(report)
    assert data["modules"]["b"]["response_time_s"] == 0.002
    assert data["placement"]["assignment"] == {"a": "cpu0", "b": "cpu0"}
    assert data["placement"]["bus_traffic_hz"] == 0.0


def test_cycles_of_blocking_protocols_and_misses_are_reported():
    report = analyse(_tcs("syn/syn", wcet_b=ms(12)))
    assert not report.ok
    assert report.timing.tasks["b"].response_ns is None
    assert "b                    prio  2  R =      — ms  D =     10 ms  MAY MISS its deadline" \
        in to_text(report)
    assert report.cycles and all(set(c.modules) == {"a", "b"} for c in report.cycles)
    assert report.placement is None and "fits on no processor" in report.placement_error


def test_dot_draws_processors_resources_and_protocols():
    dot = to_dot(_tcs("asyn/syn"))
    assert dot.startswith('digraph "Pair" {')
    assert 'subgraph cluster_1 { label="cpu1";' in dot
    assert '"arm" [shape=doubleoctagon];' in dot
    assert '"a" -> "b" [label="y→x\\nasyn/syn", style=bold];' in dot
