"""Benchmark: compile time (parse + lower + compile) against program size.

    .venv/bin/python bench/bench_compile.py            # from the repository root
    .venv/bin/python bench/bench_compile.py --quick    # fewer repetitions, N = 4…9

Two families, generated as plan-language text (``bench/_missions.py``):

- ``SeqK``: sequential missions of K = 10, 100, 300, 1000, 3000 top-level statements
  (``emit``, ``await``, ``if``…, about K × 2/5 control states). Target: ≤ 1 s for K = 1000.
- ``ParN``: ``par { await A1; } || … || { await AN; } emit O;`` for N = 4…12: 2^N + 1 states
  and 3^N + 1 transitions (a state waiting for k signals tests each of them: 2^k leaves).

Baselines measured in the same command:

- parsing alone (the lark LALR parser, the floor of any compilation of that text): the ratio
  total / parse says what lowering and automaton construction add on top;
- linear scaling: time per statement at K against time per statement at K = 100 (1.0× is
  perfectly linear); for ParN, time per transition and per branch (constant when the cost
  is proportional to transitions × N), and the growth from N − 1 to N (3^N predicts ≈ 3×).

The parser's grammar is built once before anything is timed (it is cached per process).
Each figure is the median of several runs.

Exit status 0 when every target is met, 1 when one is MISSED (2 is bad input, as for
orccad).

Needs: no extra: ORCCAD's own dependencies.
"""

from __future__ import annotations

import argparse
import gc
import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _missions import ABRO, machine, par_of_awaits, sequential  # noqa: E402

from orccad_app.lang.parser import parse  # noqa: E402
from orccad_app.reactive.compiler import compile_program  # noqa: E402
from orccad_app.reactive.lower import lower_mission  # noqa: E402


def measure(text: str, runs: int) -> dict:
    """Median times (s) of parse, lower and compile over ``runs`` runs, and the automaton."""
    parse_s, lower_s, compile_s = [], [], []
    automaton = None
    for _ in range(runs):
        gc.collect()
        t0 = time.perf_counter()
        program = parse(text, "bench.orc")
        t1 = time.perf_counter()
        kernel = lower_mission(program, program.missions[0])
        t2 = time.perf_counter()
        automaton = compile_program(kernel)
        t3 = time.perf_counter()
        parse_s.append(t1 - t0)
        lower_s.append(t2 - t1)
        compile_s.append(t3 - t2)
    med = statistics.median
    result = dict(parse=med(parse_s), lower=med(lower_s), compile=med(compile_s),
                  states=automaton.state_count, transitions=automaton.transition_count)
    result["total"] = result["parse"] + result["lower"] + result["compile"]
    return result


def ms(seconds: float) -> str:
    return f"{seconds * 1000:9.1f}"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="fewer runs, N = 4…9")
    args = parser.parse_args(argv)
    sizes = (10, 100, 300, 1000, 3000)
    max_n = 9 if args.quick else 12

    print(f"# compile benchmark — {machine()}")
    parse(ABRO, "warm.orc")  # build the grammar once (≈ 0.2 s, not part of any figure)
    print("# times in ms, median of runs; total = parse + lower + compile")

    print()
    header = (f"{'mission':<8} {'stmts':>5} {'states':>6} {'trans.':>7} | {'parse':>9} "
              f"{'lower':>9} {'compile':>9} {'total':>9} | {'total/parse':>11} "
              f"{'µs/stmt':>8} {'vs K=100':>8}")
    print(header)
    print("-" * len(header))
    seq = {}
    for k in sizes:
        runs = 3 if args.quick else (5 if k <= 1000 else 3)
        seq[k] = r = measure(sequential(k), runs)
        per = r["total"] / k * 1e6
        seq[k]["per"] = per
        base = seq.get(100, r)["per"] if 100 in seq else per
        print(f"{'Seq' + str(k):<8} {k:>5} {r['states']:>6} {r['transitions']:>7} | "
              f"{ms(r['parse'])} {ms(r['lower'])} {ms(r['compile'])} {ms(r['total'])} | "
              f"{r['total'] / r['parse']:>10.1f}× {per:>8.1f} {per / base:>7.2f}×", flush=True)

    print()
    header = (f"{'mission':<8} {'N':>5} {'states':>6} {'trans.':>7} | {'parse':>9} "
              f"{'lower':>9} {'compile':>9} {'total':>9} | {'total/parse':>11} "
              f"{'µs/trans':>8} {'/trans/N':>8} {'vs N-1':>7}")
    print(header)
    print("-" * len(header))
    par = {}
    for n in range(4, max_n + 1):
        runs = 1 if n >= 10 else (3 if args.quick or n == 9 else 5)
        par[n] = r = measure(par_of_awaits(n), runs)
        r["per"] = r["total"] / r["transitions"] * 1e6
        growth = f"{r['total'] / par[n - 1]['total']:>6.1f}×" if n - 1 in par else f"{'':>7}"
        print(f"{'Par' + str(n):<8} {n:>5} {r['states']:>6} {r['transitions']:>7} | "
              f"{ms(r['parse'])} {ms(r['lower'])} {ms(r['compile'])} {ms(r['total'])} | "
              f"{r['total'] / r['parse']:>10.1f}× {r['per']:>8.1f} {r['per'] / n:>8.2f} "
              f"{growth}", flush=True)

    print()
    t1000 = seq[1000]["total"]
    ok = t1000 <= 1.0
    print(f"target: compile (parse + lower + compile) of a 1000-statement sequential mission "
          f"≤ 1 s: {t1000:.3f} s — {'MET' if ok else 'MISSED'}")
    print(f"scaling: time per statement at K = 1000 is {seq[1000]['per'] / seq[100]['per']:.2f}× "
          f"and at K = 3000 {seq[3000]['per'] / seq[100]['per']:.2f}× the one at K = 100")
    last = par[max_n]
    print(f"ParN: compile time follows the 3^N transitions (≈ ×3 per branch) times N (each "
          f"transition is one walk over the N branches): {last['per']:.0f} µs per transition, "
          f"{last['per'] / max_n:.1f} µs per transition and branch, for N = {max_n}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
