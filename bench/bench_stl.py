"""Benchmark: robustness of signal properties by the linear evaluator
(``orccad_app.verify.stl_eval``, what runs and campaigns use) against rtamt's offline monitor
(``orccad_app.verify.stl_rtamt``, the textbook implementation it replaced), in the same
command, on one random run.

    .venv/bin/python bench/bench_stl.py            # 4 000 samples, windows of 20 and 80 samples
    .venv/bin/python bench/bench_stl.py --quick    # 2 000 samples, windows of 20 and 40

For each formula and window width ``w`` (samples): the time of each evaluator (the linear one best of
3, rtamt once, its parse excluded: it is cached) and their ratio; the values are checked equal. rtamt's
bounded ``until`` / ``since`` cost ``O(n·w²)``, its bounded ``always`` / ``eventually``
``O(n·w)``; the linear evaluator ``O(n)`` whatever ``w`` — the ratio grows with ``w``.

Needs: the ``test`` extra (``pip install -e '.[test]'``: rtamt, the reference it is timed
against).
"""

from __future__ import annotations

import argparse
import random
import time

import numpy as np

from orccad_app.verify import stl_tree as t
from orccad_app.verify.stl_eval import evaluate
from orccad_app.verify.stl_rtamt import rtamt_robustness
from orccad_app.verify.stl_tree import Direction

PERIOD_NS = 1_000_000


def formulas(width: int) -> dict[str, t.Node]:
    high = width * PERIOD_NS
    x_small = t.Margin("<", t.Var("s0"), t.Const(0.9))
    y_big = t.Margin(">", t.Var("s1"), t.Const(0.5))
    return {
        "always (x < .9 until[0,w] y > .5)": t.Window(
            "always", Direction.FUTURE, t.Until(Direction.FUTURE, x_small, y_big, 0, high)),
        "always (x < .9 since[0,w] y > .5)": t.Window(
            "always", Direction.FUTURE, t.Until(Direction.PAST, x_small, y_big, 0, high)),
        "always (y > .5 -> eventually[0,w] x < .9)": t.Window(
            "always", Direction.FUTURE, t.Junction(
                "implies", y_big, t.Window("eventually", Direction.FUTURE, x_small, 0, high))),
    }


def best_of(function, repeat: int = 3) -> tuple[float, float]:
    value, best = 0.0, float("inf")
    for _ in range(repeat):
        start = time.perf_counter()
        value = function()
        best = min(best, time.perf_counter() - start)
    return value, best


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args()
    samples, widths = (2_000, (20, 40)) if args.quick else (4_000, (20, 80))
    rng = random.Random(28)
    run = {name: [rng.random() for _ in range(samples)] for name in ("s0", "s1")}
    arrays = {name: np.asarray(values) for name, values in run.items()}
    print(f"{samples} samples; linear: best of 3, rtamt: one evaluation")
    print(f"{'formula':44} {'w':>4} {'rtamt [s]':>10} {'linear [s]':>11} {'ratio':>8}")
    for width in widths:
        for name, tree in formulas(width).items():
            rtamt_robustness(tree, {k: v[:2] for k, v in run.items()}, PERIOD_NS)  # parse
            reference, old = best_of(lambda f=tree: rtamt_robustness(f, run, PERIOD_NS), 1)
            value, new = best_of(lambda f=tree: evaluate(f, arrays, PERIOD_NS))
            assert value == reference, (name, value, reference)
            print(f"{name:44} {width:4} {old:10.3f} {new:11.4f} {old / new:7.0f}×")


if __name__ == "__main__":
    main()
