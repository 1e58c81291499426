"""Benchmark: ``orccad check`` time against model size (states of the composition).

    .venv/bin/python bench/bench_check.py            # from the repository root
    .venv/bin/python bench/bench_check.py --quick    # N up to 12

Missions of N Robot-Tasks (generated as plan-language text, each task with a type-1, a
type-2 and a type-3 exception and a 1 s duration), in two families:

- ``SeqN``: the N tasks in sequence on one robot, each run in a ``try … catch``;
- ``Par2xN``: two robots, N/2 tasks in sequence on each, the two sequences in ``par``
  (the composition is the product of the two branches).

Each mission is checked with 5 properties (mutual exclusion on a robot, a hand-over, a
recovery, fatal → aborted, termination under fairness: one liveness property with N + 2
fairness sets) plus the 4 built-in ones. Target: N = 20 with 5 properties in at most 1 s
(issue 27; issue 14 asked 5 s).

Baseline measured in the same command: the compile time of the same mission (parse, check,
lower, compile, minimize): the ratio check / compile says what the proofs cost on top.

Exit status 0 when every target is met, 1 when one is MISSED (2 is bad input, as for
orccad).

Needs: no extra: ORCCAD's own dependencies.
"""

from __future__ import annotations

import argparse
import functools
import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from orccad_app.lang.names import check  # noqa: E402
from orccad_app.lang.parser import parse  # noqa: E402
from orccad_app.plugin_host.host import PluginHost  # noqa: E402
from orccad_app.robottask.model import check_tasks  # noqa: E402
from orccad_app.verify.checker import check_mission  # noqa: E402
from orccad_app.robottask.composition import compose  # noqa: E402

TARGET_SECONDS = 1.0

TASK = """robottask T{i}() on {robot} {{
    duration 1 s;
    task_function joint_tracking(trajectory = cosine(q0 = [0.5, 0.5, 0.5], omega = pi));
    law pid(kp = 400.0, kv = 40.0);
    module traj : trajectory  period 1 ms wcet 0.1 ms on cpu0 priority 2;
    module ctrl : control_law period 1 ms wcet 0.3 ms on cpu0 priority 1;
    module jl   : joint_limits(margin = 0.05) period 5 ms wcet 0.05 ms on cpu0 priority 3;
    connect traj.qd -> ctrl.qd;
    connect traj.qd_dot -> ctrl.qd_dot;
    connect {robot}.q -> ctrl.q;
    connect {robot}.qdot -> ctrl.qdot;
    connect ctrl.tau -> {robot}.tau;
    connect {robot}.q -> jl.q;
    exception JointLimit from jl : fatal;
    exception TrackingLost from tracking_error(max = 0.2) : abort;
    exception Saturated from torque_saturation : adjust ctrl.kp = 200.0;
}}
"""



@functools.cache
def _host() -> PluginHost:
    """The installed plugins, loaded once for the whole benchmark (outside the timings)."""
    return PluginHost.load()

def _runs(indices: list[int]) -> str:
    return " ".join(f"try {{ run T{i}(); }} catch TrackingLost {{ emit Lost; }}"
                    for i in indices)


def mission(n: int, parallel: bool) -> str:
    """The text of a mission of ``n`` Robot-Tasks and its 5 properties."""
    robots = ["r1", "r2"] if parallel else ["r1"]
    tasks = [(i, robots[(i - 1) % len(robots)]) for i in range(1, n + 1)]
    text = "".join(f"robot {r} : arm3dof;\n" for r in robots)
    text += "".join(TASK.format(i=i, robot=r) for i, r in tasks)
    branches = [[i for i, r in tasks if r == robot] for robot in robots]
    if parallel:
        body = "par { " + " } || { ".join(_runs(b) for b in branches) + " }"
    else:
        body = _runs(branches[0])
    same = branches[0]
    text += f"""
mission M {{
    output Lost, Done;
    {body}
    emit Done;
}}
property M.exclusive: never (active(T{same[0]}) and active(T{same[1]}));
property M.handover: always (started(T{same[1]}) -> once (ended(T{same[0]}) or Lost));
property M.recovery: always (raised(TrackingLost) -> (Lost or aborted));
property M.fatal_aborts: always (raised(JointLimit) -> aborted);
property M.terminates: eventually (Done or aborted);

"""
    return text


def measure(n: int, parallel: bool, repeat: int) -> dict:
    text = mission(n, parallel)
    compiles, checks = [], []
    report = None
    for _ in range(repeat):
        start = time.perf_counter()
        program = parse(text, "bench.orc")
        check(program)
        check_tasks(program, _host())
        compose(program, program.missions[0])
        compiles.append(time.perf_counter() - start)
        start = time.perf_counter()
        program = parse(text, "bench.orc")
        check(program)
        check_tasks(program, _host())
        report = check_mission(program, program.missions[0])
        checks.append(time.perf_counter() - start)
    assert report is not None and report.holds, [o for o in report.outcomes if not o.holds]
    return {"automaton": report.automaton_states,
            "model": report.model_states, "steps": report.model_steps or 0,
            "properties": sum(o.kind == "property" for o in report.outcomes),
            "compile": statistics.median(compiles), "check": statistics.median(checks)}


#: ParRxK goals (issue 33): R robots in ``par``, K Robot-Tasks each, proved within these seconds.
GRID_TARGETS = {(4, 2): 1.0, (8, 4): 10.0, (16, 2): 60.0}


def measure_grid(robots: int, tasks: int) -> dict:
    """``orccad check`` (engine auto) of the robot grid; baseline: its compile to the
    lowered kernel (parse, check, lower), the work every engine does first."""
    from _missions import robot_grid

    text = robot_grid(robots, tasks)
    start = time.perf_counter()
    program = parse(text, "grid.orc")
    check(program)
    check_tasks(program, _host())
    compose(program, program.missions[0], lazy=True)
    lower = time.perf_counter() - start
    start = time.perf_counter()
    program = parse(text, "grid.orc")
    check(program)
    check_tasks(program, _host())
    report = check_mission(program, program.missions[0])
    seconds = time.perf_counter() - start
    assert report.holds, [o for o in report.outcomes if not o.holds]
    return {"engine": report.engine, "states": report.automaton_states,
            "lower": lower, "check": seconds}


def grid_table() -> bool:
    """The ParRxK family; True when every goal is met."""
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    print(f"\n{'mission':<10} {'engine':>9} {'control states':>15} {'lower s':>8} "
          f"{'check s':>8} {'check/lower':>11} {'goal s':>7}")
    met = True
    for (robots, tasks), goal in GRID_TARGETS.items():
        row = measure_grid(robots, tasks)
        ok = row["check"] <= goal
        met = met and ok
        print(f"Par{robots}x{tasks:<5} {row['engine']:>9} {row['states']:>15} "
              f"{row['lower']:>8.3f} {row['check']:>8.3f} {row['check'] / row['lower']:>10.1f}x "
              f"{goal:>7g} {'met' if ok else 'MISSED'}")
    return met


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="N up to 12, one run each")
    args = parser.parse_args(argv)
    sizes = [4, 8, 12] if args.quick else [4, 8, 12, 16, 20]
    repeat = 1 if args.quick else 3
    _host()  # plugins loaded once, before timing
    measure(4, False, 1)  # warm-up: grammar and imports
    print(f"{'mission':<10} {'automaton':>9} {'model':>7} {'steps':>7} {'props':>5} "
          f"{'compile s':>9} {'check s':>8} {'check/compile':>13}")
    print("(check: parse, compile and every proof; compile: parse and compile alone)")
    worst = 0.0
    for parallel in (False, True):
        for n in sizes:
            row = measure(n, parallel, repeat)
            name = f"Par2x{n // 2}" if parallel else f"Seq{n}"
            print(f"{name:<10} {row['automaton']:>9} {row['model']:>7} {row['steps']:>7} "
                  f"{row['properties']:>5} {row['compile']:>9.3f} {row['check']:>8.3f} "
                  f"{row['check'] / row['compile']:>12.1f}x")
            if n == 20:
                worst = max(worst, row["check"])
    grid_met = grid_table()
    if not args.quick:
        verdict = "met" if worst <= TARGET_SECONDS else "MISSED"
        print(f"target: 20 Robot-Tasks + 5 properties in at most {TARGET_SECONDS:g} s: {verdict} "
              f"(worst {worst:.2f} s)")
        return 0 if worst <= TARGET_SECONDS and grid_met else 1
    return 0 if grid_met else 1


if __name__ == "__main__":
    sys.exit(main())
