"""Campaign throughput: runs per wall second with 1 vs 2 workers, pool vs Dask, cost of a run.

A campaign is as fast as its runs. On short AUV runs (``missions/auv_survey.orc``, a 30 s
horizon, a leak with probability 0.3, the trim and a WCET drawn per run) this prints:

1. **the cost of one run**, split: ``orccad run`` as a fresh process (interpreter, imports,
   plugins, parse, check, compile, plan, run), then in one process: compiling the mission
   (done once per campaign), planning one setting (per run), creating the MuJoCo plant from its
   MJCF file (per run: what a "reset instead of reload" would save), and the run itself;
2. **runs per wall second** of the same campaign on a process pool of 1 and of 2 workers, and
   the speed-up (target >= 1.8 on 2 idle cores);
3. **the same on a Dask LocalCluster** of 2 single-threaded worker processes on loopback,
   against the pool of 2 (target: within 15 %), and that both give the same rows.

Each measurement is the best of ``--repeat`` (the machine is shared; the best is the least
disturbed). Exit status 0 when every target measured is met, 1 when one is MISSED.

Needs: part 3 needs the ``cluster`` extra (``pip install -e '.[cluster]'``: Dask); without
it, or with ``--no-dask``, part 3 is skipped with a message.

    python bench/bench_campaign.py [--runs 16] [--repeat 2] [--no-dask]
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import mujoco

from orccad_app.campaign.adapter import CompiledMission, execute
from orccad_app.campaign.executor import PoolBackend
from orccad_app.campaign.runner import Campaign, CampaignOptions
from orccad_app.campaign.setting import draw_setting
from orccad_app.campaign.spec import parse_spec

ROOT = Path(__file__).resolve().parents[1]
AUV = str(ROOT / "missions" / "auv_survey.orc")
SPEC = """\
mission = "AuvSurvey"
seed = 11
until_s = 30
[params]
"auv.cb_height_m" = "U(0.03, 0.07)"
[timing]
"Dive.pilot.wcet_ms" = "U(0.5, 3)"
[[inject]]
event = "auv.leak=1@U(8, 12)"
probability = 0.3
"""


def best(repeat: int, action) -> float:
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        action()
        times.append(time.perf_counter() - start)
    return min(times)


def run_cost(repeat: int) -> None:
    spec = parse_spec(SPEC)
    setting = draw_setting(spec, 0, 30.0)
    process = best(repeat, lambda: subprocess.run(
        [sys.executable, "-m", "orccad_app.cli", "run", AUV, *setting.run_args()],
        capture_output=True, check=False))
    start = time.perf_counter()
    compiled = CompiledMission(AUV)  # cold: plugins loaded, parse, check, compile
    compile_s = time.perf_counter() - start
    plan_s = best(repeat, lambda: compiled.plan(setting))
    path = compiled.plan(setting).plants[0].path
    plant_s = best(repeat, lambda: mujoco.MjData(mujoco.MjModel.from_xml_path(path)))
    run_s = best(repeat, lambda: execute(compiled, setting))
    print("1. cost of one run (30 s simulated)")
    print(f"   orccad run, fresh process        {process:7.3f} s")
    print(f"   load + compile (once, cold)      {compile_s:7.3f} s")
    print(f"   plan one setting (per run)       {plan_s:7.3f} s")
    print(f"     of which MuJoCo plant from MJCF {plant_s:6.4f} s "
          f"({100 * plant_s / run_s:.1f} % of a run)")
    print(f"   run it in the campaign's worker  {run_s:7.3f} s "
          f"(the process costs {process / run_s:.1f}x that)")


def campaign(backend, runs: int, db: str) -> tuple[float, list]:
    spec = parse_spec(SPEC)
    start = time.perf_counter()
    result = Campaign(AUV, spec, CampaignOptions(runs=runs, db=db)).run(backend=backend)
    wall = time.perf_counter() - start
    return runs / wall, [(r.index, r.setting.seed, r.outcome, r.sim_time_s)
                         for r in result.records]


SPEED_UP_TARGET = 2 * 0.9
"""Pool of 2 workers against 1: at least 1.8 runs per run on 2 idle cores."""
DASK_TARGET = 0.85
"""Dask LocalCluster of 2 workers against the pool of 2: within 15 %."""


def dask_missing() -> str | None:
    """Why part 3 cannot run here (Dask is the optional ``cluster`` extra), else None."""
    import importlib.util

    if importlib.util.find_spec("distributed") is None:
        return "Dask is not installed (pip install -e '.[cluster]')"
    return None


def _verdict(ok: bool) -> str:
    return "met" if ok else "MISSED"


def throughput(runs: int, repeat: int, dask: bool) -> bool:
    """Parts 2 and 3; True when their targets are met."""
    rates: dict[str, float] = {}
    rows = {}
    with tempfile.TemporaryDirectory() as folder:
        def measure(name, make_backend):
            found = []
            for attempt in range(repeat):
                rate, rows[name] = campaign(make_backend(), runs,
                                            f"{folder}/{name}-{attempt}.db")
                found.append(rate)
            rates[name] = max(found)

        measure("pool-1", lambda: PoolBackend(1))
        measure("pool-2", lambda: PoolBackend(2))
        if dask:
            import distributed

            from orccad_app.campaign.executor import DaskBackend

            with distributed.LocalCluster(n_workers=2, threads_per_worker=1,
                                          host="127.0.0.1", dashboard_address=None) as cluster, \
                    distributed.Client(cluster) as client:
                client.run(lambda: CompiledMission(AUV))  # warm the workers' imports
                measure("dask-2", lambda: DaskBackend(client))
    speed_up = rates['pool-2'] / rates['pool-1']
    met = speed_up >= SPEED_UP_TARGET
    print(f"2. runs per wall second ({runs} runs, best of {repeat})")
    print(f"   pool, 1 worker   {rates['pool-1']:6.2f} runs/s")
    print(f"   pool, 2 workers  {rates['pool-2']:6.2f} runs/s   "
          f"speed-up {speed_up:.2f}x (target >= {SPEED_UP_TARGET:g}: {_verdict(met)})")
    if dask:
        same = rows["dask-2"] == rows["pool-2"]
        ratio = rates['dask-2'] / rates['pool-2']
        met = met and ratio >= DASK_TARGET and same
        print(f"3. Dask LocalCluster, 2 workers  {rates['dask-2']:6.2f} runs/s   "
              f"dask / pool {ratio:.2f} (target >= {DASK_TARGET:g}: "
              f"{_verdict(ratio >= DASK_TARGET)}); same rows as the pool: {same}")
    return met


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=16)
    parser.add_argument("--repeat", type=int, default=2)
    parser.add_argument("--no-dask", action="store_true")
    args = parser.parse_args()
    print(f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")
    run_cost(args.repeat)
    missing = None if args.no_dask else dask_missing()
    met = throughput(args.runs, args.repeat, not args.no_dask and missing is None)
    if args.no_dask or missing:
        print(f"3. Dask: skipped ({'--no-dask' if args.no_dask else missing})")
    return 0 if met else 1


if __name__ == "__main__":
    sys.exit(main())
