"""Executive kernel benchmark: ORCCAD's own discrete-event kernel against SimPy.

Workload: 3 periodic tasks x N jobs each (default N = 100 000) on one fixed-priority
preemptive processor; every job of the lowest task is preempted twice:

=====  ==========  ======  ========  ========
task   period      wcet    offset    priority
=====  ==========  ======  ========  ========
A      1 ms        300 us  0         3 (low)
B      1 ms        200 us  100 us    2
C      1 ms        100 us  150 us    1 (high)
=====  ==========  ======  ========  ========

The ORCCAD side is the full executive (``Simulation`` with Module-Tasks, statistics, observer
hooks), not a stripped loop. The SimPy side models the same thing the usual SimPy way: one
process per job on a ``PreemptiveResource``. Both must find the same worst response times
(A 600 us, B 300 us, C 100 us), which the script checks. It prints wall times and the ratio
SimPy / ORCCAD (> 1 means the ORCCAD kernel is faster).

    python bench/bench_kernel.py [--jobs N]

Needs: the ``bench`` extra for its baseline (``pip install -e '.[bench]'``: SimPy); without it,
the baseline is skipped with a message.
"""

from __future__ import annotations

import argparse
import time

from orccad_app.executive import Processor, Simulation
from orccad_app.tcs import TCS, ModuleTask, us

TASKS = [  # name, period_ns, wcet_ns, offset_ns, priority
    ("A", us(1000), us(300), 0, 3),
    ("B", us(1000), us(200), us(100), 2),
    ("C", us(1000), us(100), us(150), 1),
]
EXPECTED = {"A": us(600), "B": us(300), "C": us(100)}


def run_orccad(jobs: int) -> dict[str, int]:
    tcs = TCS("bench")
    for name, period, wcet, offset, priority in TASKS:
        tcs.add(ModuleTask(name, period, wcet, offset_ns=offset, priority=priority))
    sim = Simulation(tcs, processors=[Processor("cpu0")])
    sim.activate()
    stats = sim.run(jobs * us(1000))
    for name in stats.tasks:
        assert stats.tasks[name].completed == jobs, (name, stats.tasks[name])
    return {name: s.response_max_ns for name, s in stats.tasks.items()}


def run_simpy(jobs: int) -> dict[str, int]:
    import simpy

    env = simpy.Environment()
    cpu = simpy.PreemptiveResource(env, capacity=1)
    worst = {name: 0 for name, *_ in TASKS}
    done = {name: 0 for name, *_ in TASKS}

    def job(name: str, wcet: int, priority: int, release: int):
        remaining = wcet
        while remaining > 0:
            with cpu.request(priority=priority, preempt=True) as request:
                yield request
                start = env.now
                try:
                    yield env.timeout(remaining)
                    remaining = 0
                except simpy.Interrupt:
                    remaining -= env.now - start
        worst[name] = max(worst[name], env.now - release)
        done[name] += 1

    def source(name: str, period: int, wcet: int, offset: int, priority: int):
        yield env.timeout(offset)
        while True:
            env.process(job(name, wcet, priority, env.now))
            yield env.timeout(period)

    for task in TASKS:
        env.process(source(*task))
    env.run(until=jobs * us(1000))
    assert all(count == jobs for count in done.values()), done
    return worst


def timed(function, jobs: int) -> tuple[float, dict[str, int]]:
    start = time.perf_counter()
    result = function(jobs)
    return time.perf_counter() - start, result


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--jobs", type=int, default=100_000, help="jobs per task")
    args = parser.parse_args()
    orccad_s, orccad_worst = timed(run_orccad, args.jobs)
    assert orccad_worst == EXPECTED, orccad_worst
    print(f"workload: 3 periodic tasks x {args.jobs} jobs, FP preemptive, 2 preemptions/period")
    print(f"orccad kernel (full executive): {orccad_s:8.3f} s  "
          f"({3 * args.jobs / orccad_s:,.0f} jobs/s)")
    try:
        simpy_s, simpy_worst = timed(run_simpy, args.jobs)
    except ImportError:
        print("simpy: not installed (pip install -e '.[bench]') - no ratio")
        return
    assert simpy_worst == EXPECTED, simpy_worst
    print(f"simpy 4 (PreemptiveResource):   {simpy_s:8.3f} s  "
          f"({3 * args.jobs / simpy_s:,.0f} jobs/s)")
    print(f"ratio simpy / orccad: {simpy_s / orccad_s:.2f}")


if __name__ == "__main__":
    main()
