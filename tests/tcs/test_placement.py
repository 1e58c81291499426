"""Placement suggestion: minimal bus traffic under a utilization bound."""

from __future__ import annotations

import pytest

from orccad_app.diagnostics import OrccadError
from orccad_app.tcs import TCS, ModuleTask, Port, ms, suggest_placement, traffic_graph


def _two_chains() -> TCS:
    """Chains a1 -> a2 -> a3 and b1 -> b2 -> b3 at 1 kHz, each 30 % of a processor."""
    tcs = TCS("chains")
    for chain in "ab":
        for i in (1, 2, 3):
            tcs.add(ModuleTask(f"{chain}{i}", ms(1), ms(0.1), None,
                               (Port("x", "in"), Port("z", "in"), Port("y", "out"))))
    tcs.add(ModuleTask("slow", ms(100), ms(1), None, (Port("y", "out"),)))
    for chain in "ab":
        tcs.connect("slow.y", f"{chain}1.x")
        tcs.connect(f"{chain}1.y", f"{chain}2.x", "asyn/syn")
        tcs.connect(f"{chain}2.y", f"{chain}3.x", "syn/syn")
    tcs.connect("a3.y", "b3.z", "asyn/synD")  # pull: 2 messages per b3 period
    tcs.connect("b3.y", "a3.z", "asyn/asyn")
    return tcs


def test_traffic_counts_writes_for_push_and_request_reply_for_pull():
    graph = traffic_graph(_two_chains())
    assert graph["a1"]["a2"]["traffic"] == pytest.approx(1000.0)
    assert graph["slow"]["a1"]["traffic"] == pytest.approx(10.0)
    assert graph["a3"]["b3"]["traffic"] == pytest.approx(3000.0)  # 2000 pull + 1000 push


def test_chains_stay_together_within_the_bound():
    placement = suggest_placement(_two_chains(), 2, bound=0.5)
    assignment = placement.assignment
    assert all(load <= 0.5 + 1e-12 for load in placement.loads.values())
    # the heaviest link (a3 <-> b3, 3 kHz) and the a chain stay on one processor; the
    # cheapest cut left is one 1 kHz link and the 10 Hz one.
    assert assignment["a1"] == assignment["a2"] == assignment["a3"] == assignment["b3"]
    assert placement.bus_traffic_hz == pytest.approx(1010.0)  # the optimum: cut b1 | b2


def test_everything_on_one_processor_when_it_fits():
    placement = suggest_placement(_two_chains(), ["p", "q"], bound=1.0)
    assert set(placement.assignment.values()) == {"p"}
    assert placement.bus_traffic_hz == 0.0


def test_infeasible_placement_names_the_module():
    tcs = TCS("big", [ModuleTask("huge", ms(1), ms(0.9))])
    with pytest.raises(OrccadError, match="module-task 'huge'.*fits on no processor"):
        suggest_placement(tcs, 3, bound=0.69)
