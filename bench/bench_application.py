"""Compile time of missions with 10, 100 and 1000 ``run`` statements (issue 4).

Each mission runs the Robot-Task of missions/arm_pid.orc N times in sequence with different
gains. Timed separately: parse + name checks, the Robot-Task checks against the plugin
registries (one instantiation per run), and lowering + compilation of the composed
automaton. The baseline, in the same command, is the compile time of a mission of N plain
``await`` statements: the ratio says what a ``run`` costs relative to the simplest waiting
statement.

    .venv/bin/python bench/bench_application.py [--quick]

Exit status 0 when every target is met, 1 when one is MISSED (2 is bad input, as for
orccad).

Needs: no extra: ORCCAD's own dependencies.
"""

from __future__ import annotations

import argparse
import functools
import os
import sys
import statistics
import time
from pathlib import Path

from orccad_app.lang.names import check
from orccad_app.lang.parser import parse
from orccad_app.plugin_host.host import PluginHost
from orccad_app.reactive.compiler import compile_program
from orccad_app.reactive.lower import lower_mission
from orccad_app.robottask.application import ApplicationLowerer
from orccad_app.robottask.model import check_tasks

ROOT = Path(__file__).resolve().parents[1]
TASK = (ROOT / "missions" / "arm_pid.orc").read_text().split("mission ArmPID")[0]



@functools.cache
def _host() -> PluginHost:
    """The installed plugins, loaded once for the whole benchmark (outside the timings)."""
    return PluginHost.load()

def run_mission(n: int) -> str:
    runs = "\n".join(f"    run TrackPID(kp = {300.0 + i % 7 * 50.0});" for i in range(n))
    return TASK + f"mission Runs {{\n{runs}\n}}\n"


def await_mission(n: int) -> str:
    awaits = "\n".join("    await Go;" for _ in range(n))
    return f"mission Awaits {{\n    input Go;\n{awaits}\n}}\n"


def timed(fn, repeat: int) -> float:
    samples = []
    for _ in range(repeat):
        start = time.perf_counter()
        fn()
        samples.append(time.perf_counter() - start)
    return statistics.median(samples)


def measure(n: int, repeat: int) -> dict:
    text = run_mission(n)
    program = parse(text, "runs.orc")
    host = _host()
    mission = program.missions[0]
    plain = parse(await_mission(n), "awaits.orc")
    figures = {
        "parse": timed(lambda: check(parse(text, "runs.orc")), repeat),
        "tasks": timed(lambda: check_tasks(program, host), repeat),
        "compile": timed(lambda: compile_program(
            lower_mission(program, mission, ApplicationLowerer)), repeat),
        "baseline": timed(lambda: compile_program(
            lower_mission(plain, plain.missions[0])), repeat),
    }
    figures["states"] = compile_program(lower_mission(program, mission, ApplicationLowerer)).state_count
    return figures


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer repetitions")
    args = parser.parse_args()
    repeat = 1 if args.quick else 3
    _host()  # load the plugins once, outside the timings
    print(f"{'runs':>6} {'states':>7} {'parse+check':>12} {'task checks':>12} "
          f"{'lower+compile':>14} {'total':>9} {'N awaits':>9} {'ratio':>6}")
    total = 0.0
    for n in (10, 100, 1000):
        f = measure(n, repeat)
        total = f["parse"] + f["tasks"] + f["compile"]
        print(f"{n:>6} {f['states']:>7} {f['parse'] * 1e3:>10.1f}ms {f['tasks'] * 1e3:>10.1f}ms "
              f"{f['compile'] * 1e3:>12.1f}ms {total * 1e3:>7.0f}ms {f['baseline'] * 1e3:>7.1f}ms "
              f"{f['compile'] / f['baseline']:>5.1f}x", flush=True)
    ok = total < 1.0
    print(f"target: 1000 runs compile (parse + checks + lower + compile) in < 1 s: "
          f"{total:.2f} s — {'MET' if ok else 'MISSED'} (load average "
          f"{os.getloadavg()[0]:.1f} on {os.cpu_count()} cores)")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
