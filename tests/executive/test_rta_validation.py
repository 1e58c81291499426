"""Validation (a): simulated worst-case response times equal the response-time analysis for
fixed-priority task sets released together at t = 0 (the critical instant)."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from orccad_app.executive import Processor, Simulation
from orccad_app.tcs import TCS, ModuleTask, ms, response_time_analysis, us


def _simulate(tasks, until_ns, context_switch_ns=0):
    sim = Simulation(TCS("rta", tasks),
                     processors=[Processor("cpu0", context_switch_ns=context_switch_ns)])
    sim.activate()
    return sim.run(until_ns)


TASK_SETS = [
    [(5, 1), (10, 2), (20, 5)],            # harmonic, U = 0.65
    [(7, 2), (12, 3), (20, 5)],            # R = 2, 5, 12
    [(3, 1), (5, 1), (15, 4)],             # U = 0.79, R = 1, 2, 9
    [(4, 1), (6, 2), (10, 1), (14, 2)],    # four tasks
    [(2.5, 0.5), (4, 1.25), (9, 2.75)],    # sub-millisecond granularity
]


@pytest.mark.parametrize("spec", TASK_SETS)
def test_simulated_worst_response_equals_rta(spec):
    tasks = [ModuleTask(f"t{i}", ms(period), ms(wcet), priority=i + 1)
             for i, (period, wcet) in enumerate(spec)]
    analysis = response_time_analysis(tasks)
    assert all(r.schedulable for r in analysis.values())
    hyper = ms(2 * 126)  # long enough for several periods of every set
    stats = _simulate(tasks, hyper)
    for task in tasks:
        assert stats.tasks[task.name].response_max_ns == analysis[task.name].response_ns
        assert stats.tasks[task.name].deadline_misses == 0


@settings(max_examples=40, deadline=None)
@given(st.lists(st.tuples(st.integers(2, 40), st.integers(1, 10)), min_size=1, max_size=5))
def test_rta_is_exact_on_random_schedulable_sets(spec):
    tasks = [ModuleTask(f"t{i}", us(100 * period), us(100 * min(wcet, period)), priority=i + 1)
             for i, (period, wcet) in enumerate(sorted(spec))]
    analysis = response_time_analysis(tasks)
    stats = _simulate(tasks, max(t.period_ns for t in tasks) + 1)
    for task in tasks:  # in priority order
        result = analysis[task.name]
        simulated = stats.tasks[task.name]
        if not result.schedulable:
            # the first unschedulable task misses its first deadline; below it, overruns
            # (skipped releases) leave the classic model, so stop comparing.
            assert simulated.completed == 0 or simulated.response_max_ns > task.deadline_ns
            break
        assert simulated.response_max_ns == result.response_ns


def test_rta_with_context_switches_bounds_the_simulation():
    tasks = [ModuleTask("a", ms(5), ms(1), priority=1),
             ModuleTask("b", ms(8), ms(2), priority=2),
             ModuleTask("c", ms(20), ms(4), priority=3, offset_ns=0)]
    switch = us(50)
    analysis = response_time_analysis(tasks, context_switch_ns=switch)
    stats = _simulate(tasks, ms(200), context_switch_ns=switch)
    for task in tasks:
        simulated = stats.tasks[task.name].response_max_ns
        assert simulated <= analysis[task.name].response_ns
        assert simulated > task.wcet_ns
