"""Benchmark: time to the first instant of a mission built on demand (``LazyAutomaton``, what
``react``, ``run``, campaigns and the TUI use) against compiling its whole automaton first
(``compile_program``, what ``compile`` and ``check`` do), in the same command.

    .venv/bin/python bench/bench_lazy.py            # ParN, N = 8, 10, 12 (full) and 16, 20 (lazy)
    .venv/bin/python bench/bench_lazy.py --quick    # full compile up to N = 10 only

``ParN`` = ``par { await A1; } || … || { await AN; } emit O;`` (2^N + 1 states, 3^N + 1
transitions; ``bench/_missions.py``). For each N: parse + lower, then either the full compile
and one reaction, or the lazy automaton and one reaction ("first instant"), then 300 instants
on a random stream (each Ai present with probability 1/N, a new reactor after each end) — on
the lazy side these build the states they reach. Both sides' outputs are checked equal on the
stream where the full automaton exists. Targets: Par12's first instant < 0.1 s; Par20 runs.

Exit status 0 when every target is met, 1 when one is MISSED (2 is bad input, as for
orccad).

Needs: no extra: ORCCAD's own dependencies.
"""

from __future__ import annotations

import argparse
import copy
import random
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _missions import machine, par_of_awaits  # noqa: E402

from orccad_app.lang.parser import parse  # noqa: E402
from orccad_app.reactive.compiler import compile_program  # noqa: E402
from orccad_app.reactive.expr import Store  # noqa: E402
from orccad_app.reactive.lazy import LazyAutomaton  # noqa: E402
from orccad_app.reactive.lower import lower_mission  # noqa: E402
from orccad_app.reactive.runtime import Reactor  # noqa: E402

INSTANTS = 300


def stream(n: int) -> list[frozenset[str]]:
    rng = random.Random(n)
    return [frozenset(f"A{i}" for i in range(1, n + 1) if rng.random() < 1 / n)
            for _ in range(INSTANTS)]


def run(automaton, instants) -> list[tuple[str, ...]]:
    """Outputs per instant; after an end, a fresh reactor (a copy of a pristine one with its
    own store: ``Reactor()`` of a full automaton lowers every tree again)."""
    pristine = Reactor(automaton)
    reactor, out = copy.copy(pristine), []
    for inputs in instants:
        reaction = reactor.react(inputs)
        out.append(reaction.outputs)
        if reaction.status != "running":
            reactor = copy.copy(pristine)
            reactor.store = Store()
    return out


def measure(n: int, full: bool) -> dict:
    text = par_of_awaits(n)
    start = time.perf_counter()
    program = parse(text, "bench.orc")
    kernel = lower_mission(program, program.missions[0])
    automaton = compile_program(kernel) if full else LazyAutomaton(kernel)
    Reactor(automaton).react(set())
    first = time.perf_counter() - start
    instants = stream(n)
    start = time.perf_counter()
    outputs = run(automaton, instants)
    return dict(first=first, run=time.perf_counter() - start, outputs=outputs,
                states=automaton.state_count)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="full compile up to N = 10 only")
    args = parser.parse_args(argv)
    full_ns = (8, 10) if args.quick else (8, 10, 12)
    print(f"# lazy automaton benchmark — {machine()}")
    print(f"# first = parse + lower + build + first reaction; run = {INSTANTS} random instants")
    print()
    header = (f"{'mission':<8} | {'full: first':>11} {'run':>8} {'states':>7} | "
              f"{'lazy: first':>11} {'run':>8} {'states':>7} | {'full/lazy first':>15}")
    print(header)
    print("-" * len(header))
    parse(par_of_awaits(2), "warm.orc")  # build the grammar once (not part of any figure)
    lazy_first: dict[int, float] = {}
    ok = True
    for n in sorted({*full_ns, 12, 16, 20}):
        lazy = measure(n, full=False)
        lazy_first[n] = lazy["first"]
        line = f"{'Par' + str(n):<8} | "
        if n in full_ns:
            whole = measure(n, full=True)
            if whole["outputs"] != lazy["outputs"]:
                print(f"Par{n}: the lazy and full automata disagree")
                return 1
            line += (f"{whole['first']:>10.3f}s {whole['run']:>7.3f}s {whole['states']:>7} | ")
            ratio = f"{whole['first'] / lazy['first']:>14.0f}×"
        else:
            line += f"{'(not compiled here)':>29} | "
            ratio = ""
        line += f"{lazy['first']:>10.4f}s {lazy['run']:>7.3f}s {lazy['states']:>7} | {ratio}"
        print(line, flush=True)
    print()
    print("outputs of every instant identical between the lazy and the full automaton "
          f"(N = {', '.join(map(str, full_ns))}): yes")
    met = lazy_first[12] < 0.1
    ok = ok and met
    print(f"target: Par12 reacts its first instant in < 0.1 s: {lazy_first[12]:.4f} s — "
          f"{'MET' if met else 'MISSED'}")
    print(f"target: Par20 (2^20 + 1 states) runs {INSTANTS} instants lazily: MET")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
