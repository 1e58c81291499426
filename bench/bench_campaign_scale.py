"""Campaign scaling: thousands of short runs in flat memory, and a worker's per-run overhead.

One command prints (issue 27, target 3):

1. **per-run overhead inside a worker**: for ``--overhead-runs`` settings of the AUV campaign
   of ``bench_campaign.py`` (30 s simulated each), the time of
   :func:`~orccad_app.campaign.adapter.execute` (plan the setting, build the plants, the
   executive and the property monitor, run, gather the metrics and verdicts) against the run
   alone (``MissionRun.run``, the record's ``wall_time_s``): overhead = everything but the
   simulation, as a share of the whole (target <= 10 %);
2. **a long campaign of a short mission** (``missions/arm_pid.orc``, 50 ms simulated, the
   control law's period and execution time drawn per run) on a pool of ``--workers``: runs
   per second, and the resident memory (``VmRSS`` from ``/proc``) of the campaign's process
   and of each worker sampled every 5 % of the runs; the growth between the first sample
   after a quarter of the runs (the warm-up: the lazy automaton, caches) and the last is
   reported per 1000 runs (target: flat, no per-run growth), and the
   database is checked to hold every run.

    python bench/bench_campaign_scale.py [--runs 10000] [--workers 2] [--overhead-runs 12]

Exit status 0 when both targets are met, 1 otherwise (2 is bad input, as for orccad).

Needs: no extra: ORCCAD's own dependencies.
"""

from __future__ import annotations

import argparse
import os
import sqlite3
import sys
import tempfile
import time
from pathlib import Path

from orccad_app.campaign.adapter import CompiledMission, execute
from orccad_app.campaign.executor import PoolBackend
from orccad_app.campaign.runner import Campaign, CampaignOptions
from orccad_app.campaign.setting import draw_setting
from orccad_app.campaign.spec import parse_spec

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_campaign import AUV, SPEC as AUV_SPEC  # noqa: E402

ARM = str(ROOT / "missions" / "arm_pid.orc")
SHORT_SPEC = """\
mission = "ArmPID"
seed = 3
until_s = 0.05
[timing]
"TrackPID.ctrl.period_ms" = "choice(1, 2)"
"TrackPID.ctrl.wcet_ms" = "U(0.1, 0.9)"
"""
OVERHEAD_TARGET = 0.10
GROWTH_TARGET_KB = 64.0
"""Largest growth per 1000 runs counted as flat [kB] (allocator noise)."""


def rss_kb(pid: int) -> int:
    """Resident memory of process ``pid`` [kB] (0 if it is gone)."""
    try:
        with open(f"/proc/{pid}/status") as status:
            for line in status:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1])
    except OSError:
        pass
    return 0


def overhead(runs: int) -> float:
    spec = parse_spec(AUV_SPEC)
    compiled = CompiledMission(AUV)
    execute(compiled, draw_setting(spec, 0, 30.0))  # warm-up: imports, lazy automaton
    total = alone = 0.0
    for index in range(1, runs + 1):
        setting = draw_setting(spec, index, 30.0)
        start = time.perf_counter()
        record = execute(compiled, setting)
        total += time.perf_counter() - start
        alone += record.wall_time_s
    share = (total - alone) / total
    print(f"1. per-run overhead in a worker ({runs} AUV runs of 30 s simulated)")
    print(f"   execute {total / runs * 1e3:8.1f} ms per run, the run alone "
          f"{alone / runs * 1e3:8.1f} ms: overhead {(total - alone) / runs * 1e3:.1f} ms "
          f"= {100 * share:.1f} % (target <= {100 * OVERHEAD_TARGET:g} %)")
    return share


def scale(runs: int, workers: int) -> float:
    spec = parse_spec(SHORT_SPEC)
    samples: list[tuple[int, int, list[int]]] = []
    step = max(1, runs // 20)
    backend = PoolBackend(workers)

    def sample(done: int, limit: int, prefix: list) -> None:
        if done % step == 0 or done == limit:
            if not samples or samples[-1][0] != done:
                samples.append((done, rss_kb(os.getpid()),
                                [rss_kb(pid) for pid in backend.worker_pids()]))

    with tempfile.TemporaryDirectory() as folder:
        db = f"{folder}/scale.db"
        start = time.perf_counter()
        result = Campaign(ARM, spec, CampaignOptions(runs=runs, db=db)).run(sample, backend)
        wall = time.perf_counter() - start
        with sqlite3.connect(db) as connection:
            stored = connection.execute("SELECT COUNT(*) FROM runs").fetchone()[0]
    print(f"2. {runs} runs of a 50 ms mission on {workers} workers: {wall:.1f} s, "
          f"{runs / wall:.1f} runs/s; {stored} rows in the database "
          f"({len(result.records)} runs in the result)")
    print(f"   {'runs':>6} {'parent kB':>10} {'workers kB':>24}")
    for done, parent, children in samples:
        print(f"   {done:>6} {parent:>10} {' '.join(f'{c:>11}' for c in children):>24}")
    first = next(s for s in samples if s[0] >= runs // 4)  # after the warm-up
    last = samples[-1]
    span = (last[0] - first[0]) / 1000 or 1.0
    parent_growth = (last[1] - first[1]) / span
    worker_growth = max((b - a) / span for a, b in zip(first[2], last[2])) \
        if first[2] and len(first[2]) == len(last[2]) else 0.0
    print(f"   growth per 1000 runs from {first[0]} to {last[0]} runs: parent "
          f"{parent_growth:.1f} kB, worst worker {worker_growth:.1f} kB "
          f"(flat: <= {GROWTH_TARGET_KB:g} kB)")
    assert stored == runs, (stored, runs)
    return max(parent_growth, worker_growth)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=10000)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--overhead-runs", type=int, default=12)
    parser.add_argument("--skip-overhead", action="store_true")
    args = parser.parse_args()
    print(f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")
    share = 0.0 if args.skip_overhead else overhead(args.overhead_runs)
    growth = scale(args.runs, args.workers)
    print(f"load average {os.getloadavg()[0]:.1f} at the end")
    return 0 if share <= OVERHEAD_TARGET and growth <= GROWTH_TARGET_KB else 1


if __name__ == "__main__":
    sys.exit(main())
