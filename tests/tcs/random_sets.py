"""Seeded random TCSs for the analysis-against-executive property tests.

A set has 2–5 Module-Tasks on 1–3 processors, periods all equal (40 % of the sets), harmonic
(20 %) or drawn from harmonic and non-harmonic values (1–10 ms, some of them coprime),
execution times giving per-processor utilizations up to about 1, random priorities, optional
best-case execution times, and connections along a random DAG (no wait cycle, so no deadlock),
most of them under the protocol under test and the rest ``asyn/asyn``; a few Module-Tasks get
an offset or a deadline shorter than their period. Each set also draws a context-switch
overhead and a bus transfer time.
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass, field

from collections import Counter

from orccad_app.executive import Bus, Processor, Simulation
from orccad_app.tcs import TCS, ModuleTask, Port, us
from orccad_app.tcs.bus_delay import BusModel
from orccad_app.tcs.phasing import Activation
from orccad_app.tcs.deadlock import find_deadlock_cycles
from orccad_app.tcs.protocol import Protocol
from orccad_app.tcs.schedulability import Schedulability, analyse_timing

PERIODS_US = (1000, 1000, 2000, 2000, 3000, 4000, 5000, 5000, 6000, 10000, 2500, 7000)
"""Candidate periods [µs]; duplicates make equal periods (the synchronous protocols' usual
case) frequent."""


class Writer:
    """Writes a counter on every output port, every job (a write that is skipped cannot
    block, so every port is written)."""

    def __init__(self, outputs: tuple[str, ...]) -> None:
        self.outputs = outputs
        self.count = 0

    def compute(self, t_s: float, inputs: dict) -> dict:
        self.count += 1
        return {name: self.count for name in self.outputs}


@dataclass
class RandomSet:
    """One generated set: its TCS and the platform figures."""

    tcs: TCS
    protocol: str
    context_switch_ns: int
    transfer_ns: int
    horizon_ns: int
    interrupts: dict[str, list[int]] = field(default_factory=dict)
    """Sporadic Module-Task -> its external interrupts [ns] (besides its inputs' writes)."""
    deferred: int = 0
    """Interrupts of the last run that came too early (deferred or coalesced)."""

    def analyse(self, scheduler: str) -> Schedulability:
        return analyse_timing(self.tcs, scheduler, self.context_switch_ns,
                              BusModel(self.transfer_ns))

    def run(self, scheduler: str) -> dict[str, tuple[int, int]]:
        """Module-Task -> (deadline misses, overruns) of an executive run."""
        for task in self.tcs.module_tasks:
            task.compute = Writer(tuple(p.name for p in task.outputs))
        processors = sorted({t.processor for t in self.tcs.module_tasks})
        sim = Simulation(self.tcs, seed=0, bus=Bus(transfer_ns=self.transfer_ns),
                         processors=[Processor(p, scheduler, self.context_switch_ns)
                                     for p in processors])
        sim.activate()
        for name, instants in self.interrupts.items():
            for instant in instants:
                sim.interrupt(name, at_ns=instant)
        stats = sim.run(self.horizon_ns)
        self.deferred = sum(s.deferred + s.coalesced for s in stats.sporadic.values())
        return {name: (s.deadline_misses, s.overruns) for name, s in stats.tasks.items()}


def make_sporadic(random_set: RandomSet, seed: int) -> RandomSet:
    """The same set with one or two Module-Tasks made sporadic (minimum inter-arrival time =
    their period, no offset), each interrupted by its inputs' writes and by an external
    interrupt line whose gaps are drawn in [0.2, 3] times the minimum (so that many arrive
    too early and are deferred)."""
    rng = random.Random(seed + 7_000_003)
    tasks = list(random_set.tcs.module_tasks)
    for task in rng.sample(tasks, k=min(len(tasks), rng.randint(1, 2))):
        task.activation = Activation.SPORADIC
        task.offset_ns = 0
        instants, t = [], rng.randint(0, task.period_ns)
        while t < random_set.horizon_ns:
            instants.append(t)
            t += max(1, int(task.period_ns * rng.uniform(0.2, 3.0)))
        random_set.interrupts[task.name] = instants
    return random_set


def generate(seed: int, protocol: str) -> RandomSet:
    """The set number ``seed`` whose connections use ``protocol``."""
    rng = random.Random(seed)
    count = rng.randint(2, 5)
    cpus = [f"cpu{i}" for i in range(rng.randint(1, min(3, count)))]
    shape = rng.random()
    if shape < 0.4:  # one rate: what the synchronous protocols are for
        periods = [rng.choice(PERIODS_US)] * count
    elif shape < 0.6:  # harmonic
        base = rng.choice((1000, 2000, 2500))
        periods = [base * rng.choice((1, 1, 2, 4)) for _ in range(count)]
    else:
        periods = [rng.choice(PERIODS_US) for _ in range(count)]
    placement = [rng.choice(cpus) for _ in range(count)]
    target = {cpu: rng.uniform(0.2, 1.05) for cpu in cpus}
    share = {cpu: [rng.random() + 0.1 for _ in range(count)] for cpu in cpus}
    edges = [(i, j) for i in range(count) for j in range(i + 1, count) if rng.random() < 0.5]
    if not edges:
        edges = [(0, 1)]
    tasks = []
    for i in range(count):
        cpu = placement[i]
        weights = [share[cpu][k] for k in range(count) if placement[k] == cpu]
        u = target[cpu] * share[cpu][i] / sum(weights)
        wcet = max(1, int(periods[i] * u)) if rng.random() > 0.05 else 0
        bcet = rng.randint(0, wcet) if wcet and rng.random() < 0.3 else None
        ports = tuple(Port(f"o{j}", "out") for (k, j) in edges if k == i) + tuple(
            Port(f"i{k}", "in") for (k, j) in edges if j == i)
        offset = rng.choice((100, 250, 1000)) if rng.random() < 0.1 else 0
        deadline = rng.randint(min(wcet + 1, periods[i]), periods[i]) \
            if rng.random() < 0.15 else None
        tasks.append(ModuleTask(f"m{i}", us(periods[i]), us(wcet), ports=ports,
                                processor=cpu, priority=rng.randint(1, count),
                                bcet_ns=None if bcet is None else us(bcet),
                                deadline_ns=None if deadline is None else us(deadline),
                                offset_ns=us(offset)))
    tcs = TCS(f"set{seed}")
    for task in tasks:
        tcs.add(task)
    for (i, j) in edges:
        chosen = protocol if rng.random() < 0.8 else "asyn/asyn"
        tcs.connect(f"m{i}.o{j}", f"m{j}.i{i}", chosen)
    lcm = math.lcm(*periods)
    horizon_us = min(max(3 * lcm, 20 * max(periods)), 60_000)
    return RandomSet(tcs, protocol, us(rng.choice((0, 0, 5, 20))),
                     us(rng.choice((0, 10, 50, 200))), us(horizon_us))


@dataclass
class Survey:
    """Outcomes of the analysis against runs, per (protocol, scheduler).

    ``counts[key]`` holds ``runs``, ``clean`` (no deadline miss, no overrun), ``said_ok``
    (the analysis says schedulable), ``pessimistic`` (said unschedulable, ran clean) and
    ``unsafe`` (said schedulable, missed or overran); ``unsafe_cases`` names the latter.
    """

    counts: dict[tuple[str, str], Counter]
    unsafe_cases: list[str]
    skipped: int


def survey(sets_per_protocol: int, first_seed: int = 0,
           horizon_ns: int | None = None, sporadic: bool = False) -> Survey:
    """Generate ``sets_per_protocol`` sets per protocol, analyse and run each under FP and
    EDF (for ``horizon_ns`` instead of the set's own horizon when given; with one or two
    sporadic Module-Tasks per set when ``sporadic``). Sets with a potential deadlock cycle are
    skipped (the static analysis rejects them)."""
    counts: dict[tuple[str, str], Counter] = {}
    unsafe: list[str] = []
    skipped = 0
    protocols = [p.value for p in Protocol]
    for index, protocol in enumerate(protocols):
        for k in range(sets_per_protocol):
            seed = first_seed + k * len(protocols) + index
            random_set = generate(seed, protocol)
            if find_deadlock_cycles(random_set.tcs):
                skipped += 1
                continue
            if horizon_ns is not None:
                random_set.horizon_ns = horizon_ns
            if sporadic:
                make_sporadic(random_set, seed)
            for scheduler in ("fp", "edf"):
                said_ok = random_set.analyse(scheduler).ok
                run = random_set.run(scheduler)
                clean = not any(m or o for m, o in run.values())
                count = counts.setdefault((protocol, scheduler), Counter())
                count.update(runs=1, clean=int(clean), said_ok=int(said_ok),
                             deferred=random_set.deferred,
                             pessimistic=int(clean and not said_ok),
                             unsafe=int(said_ok and not clean))
                if said_ok and not clean:
                    unsafe.append(f"seed {seed} ({protocol}, {scheduler}): {run}")
    return Survey(counts, unsafe, skipped)


def table(result: Survey) -> str:
    """The survey as a Markdown table (the one in docs/executive.md)."""
    lines = ["| protocol | scheduler | runs | ran clean | `tcs` ok | unsafe | "
             "pessimism (clean runs `tcs` rejects) |", "|---|---|---|---|---|---|---|"]
    for (protocol, scheduler), c in result.counts.items():
        share = c["pessimistic"] / c["clean"] if c["clean"] else 0.0
        lines.append(f"| `{protocol}` | {scheduler} | {c['runs']} | {c['clean']} | "
                     f"{c['said_ok']} | {c['unsafe']} | {c['pessimistic']} ({share:.0%}) |")
    return "\n".join(lines)


if __name__ == "__main__":
    # python -m tests.tcs.random_sets [SETS_PER_PROTOCOL] [--sporadic] [--horizon-ms MS]
    import argparse
    import sys

    parser = argparse.ArgumentParser(prog="python -m tests.tcs.random_sets")
    parser.add_argument("sets", nargs="?", type=int, default=250)
    parser.add_argument("--sporadic", action="store_true")
    parser.add_argument("--horizon-ms", type=int, default=None,
                        help="run each set this long instead of its own horizon (400: drifting "
                             "phases and rare alignments show)")
    options = parser.parse_args()
    first_seed = 300_000 if options.sporadic else 900_000 if options.horizon_ms else 0
    outcome = survey(options.sets, first_seed=first_seed, sporadic=options.sporadic,
                     horizon_ns=options.horizon_ms * 1_000_000 if options.horizon_ms else None)
    print(table(outcome))
    print(f"skipped (potential deadlock): {outcome.skipped}; unsafe: {outcome.unsafe_cases}")
    sys.exit(1 if outcome.unsafe_cases else 0)
