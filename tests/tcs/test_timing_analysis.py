"""The timing analysis on the cases that matter, each checked against an executive run:
protocol blocking and rate mismatches, EDF at full load, phases from the gcd of the periods,
sporadic Module-Tasks, activation stages, the bus, and the analysis's budgets."""

from __future__ import annotations

import time

import pytest

from orccad_app.executive import Bus, Processor, Simulation
from orccad_app.tcs import TCS, ModuleTask, Port, ms, us
from orccad_app.tcs.bus_delay import BusModel
from orccad_app.tcs.phasing import Activation, Phase, next_release_gap_ns
from orccad_app.tcs.schedulability import analyse_timing
from tests.tcs.random_sets import Writer


def _pair(protocol: str, producer_ns: int, consumer_ns: int, remote: bool = True,
          producer_wcet: int = us(100), consumer_wcet: int = us(300), **consumer) -> TCS:
    """traj (producer, cpu1) -> ctrl (consumer, cpu0 or cpu1), the issue's shape."""
    tcs = TCS("pair")
    tcs.add(ModuleTask("traj", producer_ns, producer_wcet, Writer(("qd",)),
                       (Port("qd", "out"),), processor="cpu1", priority=2))
    tcs.add(ModuleTask("ctrl", consumer_ns, consumer_wcet, Writer(()), (Port("qd", "in"),),
                       processor="cpu0" if remote else "cpu1", priority=1, **consumer))
    tcs.connect("traj.qd", "ctrl.qd", protocol)
    return tcs


def _run(tcs: TCS, until_ns: int, scheduler: str = "fp", transfer_ns: int = 0):
    processors = sorted({t.processor for t in tcs.module_tasks})
    sim = Simulation(tcs, bus=Bus(transfer_ns=transfer_ns),
                     processors=[Processor(p, scheduler) for p in processors])
    sim.activate()
    return sim.run(until_ns).tasks


def test_a_syn_syn_rate_mismatch_is_unschedulable_by_construction():
    # the example: traj (2 ms, cpu1) -> ctrl (1 ms, cpu0) over syn/syn was "ok"
    tcs = _pair("syn/syn", ms(2), ms(1))
    timing = analyse_timing(tcs)
    assert not timing.ok
    problem = timing.tasks["ctrl"].problem
    assert "unschedulable by construction" in problem and "'traj' writes every 2 ms" in problem
    stats = _run(tcs, ms(500))["ctrl"]
    assert stats.deadline_misses >= 0.9 * stats.released


@pytest.mark.parametrize("protocol", ["syn/syn", "asyn/syn", "asyn/synF", "syn/asyn"])
def test_equal_rates_get_a_bounded_blocking_term_that_covers_the_run(protocol):
    tcs = _pair(protocol, ms(1), ms(1))
    timing = analyse_timing(tcs, bus=BusModel(us(50)))
    assert timing.ok
    stats = _run(tcs, ms(100), transfer_ns=us(50))
    for name, result in timing.tasks.items():
        assert stats[name].deadline_misses == 0 and stats[name].overruns == 0
        assert stats[name].response_max_ns <= result.response_ns, name
    if protocol in ("syn/syn", "asyn/syn", "asyn/synF"):
        # ctrl waits for traj's write (0.1 ms) and the transfer (50 us)
        assert timing.tasks["ctrl"].read_wait_ns == us(150)


def test_edf_at_full_load_is_schedulable_where_fixed_priority_is_not():
    tcs = TCS("full")
    tcs.add(ModuleTask("ctrl", ms(2), ms(1), Writer(()), priority=2))
    tcs.add(ModuleTask("traj", ms(3), us(1500), Writer(()), priority=1))
    fp, edf = analyse_timing(tcs, "fp"), analyse_timing(tcs, "edf")
    assert not fp.ok and "processor interference" in fp.tasks["ctrl"].problem
    assert edf.ok
    assert sum(s.deadline_misses for s in _run(tcs, ms(60), "fp").values()) > 0
    assert sum(s.deadline_misses for s in _run(tcs, ms(60), "edf").values()) == 0


def test_nearly_equal_periods_drift_through_every_phase():
    # 1 ms and 1000001 ns: gcd 1 ns, so the consumer's release drifts 1 ns per period away
    # from the producer's, through every phase: over asyn/synF it may wait ~1 ms for the next
    # write. (The run reaches that phase after ~600 s; "nearly in phase" would say 0.1 ms.)
    assert next_release_gap_ns(Phase(1_000_001), Phase(ms(1))) == ms(1) - 1
    timing = analyse_timing(_pair("asyn/synF", ms(1), 1_000_001, remote=False))
    assert not timing.ok and timing.tasks["ctrl"].response_ns is None
    # the same drift, 50 us per period, reaches the bad phases within a short run
    tcs = _pair("asyn/synF", ms(1), us(1050), remote=False)
    assert next_release_gap_ns(Phase(us(1050)), Phase(ms(1))) == us(950)
    assert not analyse_timing(tcs).ok
    assert _run(tcs, ms(50))["ctrl"].deadline_misses > 0


def test_absurd_periods_are_analysed_exactly_and_at_once():
    started = time.perf_counter()
    tcs = TCS("absurd")
    tcs.add(ModuleTask("tick", 1, 1, priority=1))
    tcs.add(ModuleTask("ctrl", ms(1), us(500), priority=2))
    for scheduler in ("fp", "edf"):
        timing = analyse_timing(tcs, scheduler)
        assert not timing.ok and timing.tasks["ctrl"].problem
    tcs = TCS("coprime")
    tcs.add(ModuleTask("a", 1_000_001, 500_000, deadline_ns=999_999, priority=1))
    tcs.add(ModuleTask("b", ms(1), 500_000, deadline_ns=999_999, priority=2))
    assert not analyse_timing(tcs, "edf").ok
    assert time.perf_counter() - started < 1.0


def test_a_sporadic_module_task_interferes_at_its_minimum_interarrival():
    def build(activation):
        tcs = TCS("s")
        tcs.add(ModuleTask("irq", ms(2), us(500), priority=1, activation=activation))
        tcs.add(ModuleTask("ctrl", ms(5), ms(1), priority=2))
        return analyse_timing(tcs)

    sporadic, periodic = build(Activation.SPORADIC), build("periodic")
    assert sporadic.ok and sporadic.tasks["ctrl"].response_ns == ms(1.5)
    assert sporadic.tasks["ctrl"] == periodic.tasks["ctrl"]


def test_waiting_on_a_sporadic_producer_has_no_bound():
    tcs = _pair("asyn/syn", ms(1), ms(5))
    tcs.module("traj").activation = Activation.SPORADIC
    timing = analyse_timing(tcs)
    assert not timing.ok and "sporadic 'traj'" in timing.tasks["ctrl"].problem
    # asyn/asyn never waits: a sporadic producer is fine there
    tcs = _pair("asyn/asyn", ms(1), ms(5))
    tcs.module("traj").activation = Activation.SPORADIC
    assert analyse_timing(tcs).ok


def test_a_module_of_an_earlier_phase_cannot_wait_for_a_later_one():
    tcs = _pair("asyn/syn", ms(1), ms(1))
    # ctrl measures in phase 2, traj only starts in phase 3
    timing = analyse_timing(tcs, groups={"ctrl": 2, "traj": 3})
    assert "starts in a later phase" in timing.tasks["ctrl"].problem
    # the other way round, the phase is unknown: a full period of the producer is charged
    timing = analyse_timing(tcs, groups={"ctrl": 3, "traj": 2})
    assert not timing.ok and timing.tasks["ctrl"].problem
    assert analyse_timing(_pair("asyn/syn", ms(1), ms(5)), groups={"ctrl": 3, "traj": 2}).ok


def test_bus_delays_are_reported_per_message_class():
    tcs = _pair("asyn/synD", ms(1), ms(2))
    timing = analyse_timing(tcs, bus=BusModel(us(100), us(40)))
    kinds = {(m.kind, m.transfer_ns): m for m in timing.messages}
    assert set(kinds) == {("request", us(40)), ("reply", us(100))}
    # both classes share the FIFO bus: each may queue behind the other
    assert kinds[("request", us(40))].queueing_ns == us(100)
    assert kinds[("reply", us(100))].queueing_ns == us(40)
    assert timing.tasks["ctrl"].read_wait_ns == 2 * us(140)
    stats = _run(tcs, ms(40), transfer_ns=us(100))
    assert stats["ctrl"].response_max_ns <= timing.tasks["ctrl"].response_ns


def test_an_overloaded_bus_is_unschedulable():
    tcs = _pair("asyn/asyn", ms(1), ms(1))
    timing = analyse_timing(tcs, bus=BusModel(ms(2)))
    assert not timing.ok and "bus is overloaded" in timing.tasks["traj"].problem


def test_context_switches_are_charged_twice_per_job():
    tcs = TCS("cs")
    tcs.add(ModuleTask("a", ms(1), us(300), priority=1))
    tcs.add(ModuleTask("b", ms(4), ms(1), priority=2))
    timing = analyse_timing(tcs, context_switch_ns=us(10))
    assert timing.tasks["a"].response_ns == us(320)
    assert timing.tasks["b"].response_ns == us(1020 + 2 * 320)


def test_a_job_of_no_execution_time_waits_for_earlier_deadlines_released_with_it():
    # found by a 400 ms run: m0 (no execution time) is dispatched after m1, whose deadline is
    # earlier, at every common release; its syn/syn partner then waited past its deadline
    tcs = TCS("zero")
    tcs.add(ModuleTask("m0", ms(3), 0, Writer(()), priority=1))
    tcs.add(ModuleTask("m1", ms(3), us(1859), Writer(()), priority=3, deadline_ns=us(2764)))
    timing = analyse_timing(tcs, "edf")
    assert timing.tasks["m0"].compute_end_ns >= us(1859)
    stats = _run(tcs, ms(30), "edf")
    assert stats["m0"].response_max_ns <= timing.tasks["m0"].response_ns
