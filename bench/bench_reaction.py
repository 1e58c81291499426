"""Benchmark: the cost of one reaction (``Reactor.react``) against py_trees ticking the same
behaviour as a behaviour tree, measured in the same command; and the lean path
(``Reactor.step``, what the executive and campaigns call: it returns the reached leaf's
precomputed ``Step`` instead of building a ``Reaction`` record) against ``react`` on the
same stream. Target: ABRO ≤ 0.5 µs median on the lean path.

    .venv/bin/python bench/bench_reaction.py            # from the repository root
    .venv/bin/python bench/bench_reaction.py --quick    # smaller streams, N = 4…8

Families (each compiled from plan-language text, parse → lower → compile):

- ``ABRO`` (``missions/abro.orc``) on a random input stream (A, B: 25 %, R: 5 %);
- ``Seq200``, a 200-statement sequential mission (``bench/_missions.py:sequential``) on
  random A, B, C (50 % each); restarted when it terminates;
- ``ParN`` = ``par { await A1; } || … || { await AN; } emit O;`` for N = 4…12 (2^N + 1
  states) on a stream where each Ai is present with probability 1/N; restarted when it
  terminates.

The baseline is py_trees (installed for benchmarking only, not a project dependency) ticking
an equivalent tree: the same input stream is fed to both and the outputs of every instant are
checked to be identical before anything is timed. Each reaction / tick is timed alone with
``time.perf_counter_ns`` (the timer's own cost is measured and subtracted), after a warm-up
pass, over several passes of the stream; medians and p90 are reported. For ABRO, a
hand-written dict-based state machine gives the floor of a Python reaction.

py_trees is ticked with ``root.tick_once()`` (no tree-level visitors or handlers — its
cheapest way to tick); "per node" is per behaviour actually ticked in that tick (counted on an
untimed pass), and "tree" the number of behaviours in the tree.

Exit status 0 when every target is met, 1 when one is MISSED (2 is bad input, as for
orccad).

Needs: the ``bench`` extra for the py_trees comparison (``pip install -e '.[bench]'``); without
it, that comparison is skipped with a message.
"""

from __future__ import annotations

import argparse
import copy
import gc
import random
import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _missions import (  # noqa: E402
    ABRO, compile_source, machine, par_of_awaits, percentile, sequential,
)

from orccad_app.reactive.expr import Store  # noqa: E402
from orccad_app.reactive.runtime import Reactor  # noqa: E402

try:
    import py_trees
    from py_trees.common import ParallelPolicy, Status
except ImportError:  # pragma: no cover - the bench says so and uses the dict baseline only
    py_trees = None

clock = time.perf_counter_ns


def timer_overhead() -> float:
    """Median cost (ns) of two back-to-back ``perf_counter_ns`` calls."""
    samples = []
    for _ in range(20_000):
        t0 = clock()
        t1 = clock()
        samples.append(t1 - t0)
    return statistics.median(samples)


# ---------------------------------------------------------------------------------- streams
def stream(inputs: tuple[str, ...], probs: dict[str, float], length: int, seed: int):
    rng = random.Random(seed)
    return [frozenset(s for s in inputs if rng.random() < probs[s]) for _ in range(length)]


def fmt_outputs(names) -> str:
    """The set of outputs of an instant as text (py_trees emits in execution order, ORCCAD in
    declaration order: both are sets)."""
    return " ".join(sorted(names)) or "-"


# ---------------------------------------------------------------------------------- ours
class FreshReactors:
    """New reactors for one automaton without re-lowering its trees each time (``Reactor()``
    costs ~1 s for the 531 442 transitions of Par12): a shallow copy of a pristine reactor
    with a data store of its own (the only mutable part it shares)."""

    def __init__(self, automaton):
        self.pristine = Reactor(automaton)

    def __call__(self) -> Reactor:
        reactor = copy.copy(self.pristine)
        reactor.store = Store()
        return reactor


class OrccadRunner:
    """Runs an automaton on a stream, with a new reactor at the instant after the mission has
    ended (status other than ``running``)."""

    def __init__(self, automaton):
        self.automaton = automaton
        self.fresh = FreshReactors(automaton)

    def outputs(self, instants) -> list[str]:
        reactor = self.fresh()
        out = []
        for inputs in instants:
            reaction = reactor.react(inputs)
            out.append(fmt_outputs(reaction.outputs))
            if reaction.status != "running":
                reactor = self.fresh()
        return out

    def time(self, instants, passes: int, overhead: float, lean: bool = False) -> list[float]:
        """Per-instant times of ``react`` (or of the lean ``step`` when ``lean``)."""
        samples: list[float] = []
        add = samples.append
        method = "step" if lean else "react"
        for _ in range(passes):
            react = getattr(self.fresh(), method)
            gc.collect()
            for inputs in instants:
                t0 = clock()
                reaction = react(inputs)
                t1 = clock()
                add(t1 - t0 - overhead)
                if reaction.status != "running":
                    react = getattr(self.fresh(), method)
        return samples


# ---------------------------------------------------------------------------------- py_trees
class Env:
    """What the py_trees behaviours read (inputs of the instant) and write (outputs)."""

    inputs: frozenset = frozenset()
    outputs: list = []


if py_trees is not None:

    class Await(py_trees.behaviour.Behaviour):
        """``await S`` (non-immediate): RUNNING on its first tick, then SUCCESS when any of
        ``signals`` is present."""

        def __init__(self, *signals: str):
            super().__init__(name="await " + "|".join(signals))
            self.signals = signals
            self.first = True

        def initialise(self) -> None:
            self.first = True

        def update(self) -> Status:
            if self.first:
                self.first = False
                return Status.RUNNING
            inputs = Env.inputs
            for s in self.signals:
                if s in inputs:
                    return Status.SUCCESS
            return Status.RUNNING

    class Present(py_trees.behaviour.Behaviour):
        """A condition: SUCCESS when the input is present in this instant."""

        def __init__(self, signal: str):
            super().__init__(name=signal + "?")
            self.signal = signal

        def update(self) -> Status:
            return Status.SUCCESS if self.signal in Env.inputs else Status.FAILURE

    class Emit(py_trees.behaviour.Behaviour):
        def __init__(self, signal: str):
            super().__init__(name="emit " + signal)
            self.signal = signal

        def update(self) -> Status:
            Env.outputs.append(self.signal)
            return Status.SUCCESS

    class Halt(py_trees.behaviour.Behaviour):
        def update(self) -> Status:
            return Status.RUNNING

    class ResetEach(py_trees.behaviour.Behaviour):
        """``loop … each R``: when R is present, stop (reset) ``body`` so that the tick that
        follows restarts it; always SUCCESS."""

        def __init__(self, signal: str, body):
            super().__init__(name="reset on " + signal)
            self.signal, self.body = signal, body

        def update(self) -> Status:
            if self.signal in Env.inputs and self.body.status != Status.INVALID:
                self.body.stop(Status.INVALID)
            return Status.SUCCESS

    def pt_abro():
        parallel = py_trees.composites.Parallel(
            "A and B", ParallelPolicy.SuccessOnAll(synchronise=True), [Await("A"), Await("B")])
        body = py_trees.composites.Sequence("body", True, [parallel, Emit("O"), Halt("halt")])
        return py_trees.composites.Sequence("ABRO", False, [ResetEach("R", body), body])

    def pt_sequential(n: int):
        def statement(i: int):
            kind = i % 5
            if kind == 0:
                return Emit("O")
            if kind == 1:
                return Await("A")
            if kind == 2:
                then = py_trees.composites.Sequence("then", False, [Present("B"), Emit("O")])
                return py_trees.composites.Selector("if B", False, [then, Emit("P")])
            if kind == 3:
                return Await("B", "C")
            return Emit("P")
        return py_trees.composites.Sequence("Seq", True, [statement(i) for i in range(n)])

    def pt_par(n: int):
        parallel = py_trees.composites.Parallel(
            "par", ParallelPolicy.SuccessOnAll(synchronise=True),
            [Await(f"A{i}") for i in range(1, n + 1)])
        return py_trees.composites.Sequence(f"Par{n}", True, [parallel, Emit("O")])


class PyTreesRunner:
    """Ticks a tree once per instant; after SUCCESS the next tick restarts it (like a fresh
    reactor after the mission has ended)."""

    def __init__(self, root):
        self.root = root
        self.size = sum(1 for _ in root.iterate())

    def outputs(self, instants) -> tuple[list[str], float]:
        self.root.stop(Status.INVALID)
        out, ticked = [], 0
        for inputs in instants:
            Env.inputs, Env.outputs = inputs, []
            ticked += sum(1 for _ in self.root.tick())
            out.append(fmt_outputs(Env.outputs))
        return out, ticked / len(instants)

    def time(self, instants, passes: int, overhead: float) -> list[float]:
        samples: list[float] = []
        add = samples.append
        tick = self.root.tick_once
        for _ in range(passes):
            self.root.stop(Status.INVALID)
            gc.collect()
            for inputs in instants:
                Env.inputs = inputs
                Env.outputs = []
                t0 = clock()
                tick()
                t1 = clock()
                add(t1 - t0 - overhead)
        return samples


# ---------------------------------------------------------------------------------- floor
def dict_abro_factory():
    """ABRO written by hand as a dict-based state machine: the floor of a Python reaction.

    States: 0 boot, 1 waiting A and B, 2 waiting A, 3 waiting B, 4 halted.
    """
    def react(state: int, inputs) -> tuple[int, tuple[str, ...]]:
        if state == 0 or "R" in inputs:
            return 1, ()
        if state == 1:
            a, b = "A" in inputs, "B" in inputs
            if a and b:
                return 4, ("O",)
            return (3 if a else 2 if b else 1), ()
        if state == 2:
            return (4, ("O",)) if "A" in inputs else (2, ())
        if state == 3:
            return (4, ("O",)) if "B" in inputs else (3, ())
        return 4, ()
    return react


def dict_abro_outputs(instants) -> list[str]:
    react, state, out = dict_abro_factory(), 0, []
    for inputs in instants:
        state, emitted = react(state, inputs)
        out.append(fmt_outputs(emitted))
    return out


def dict_abro_time(instants, passes: int, overhead: float) -> list[float]:
    react, samples = dict_abro_factory(), []
    add = samples.append
    for _ in range(passes):
        state = 0
        for inputs in instants:
            t0 = clock()
            state, _ = react(state, inputs)
            t1 = clock()
            add(t1 - t0 - overhead)
    return samples


# ---------------------------------------------------------------------------------- main
def stats(samples: list[float]) -> tuple[float, float]:
    samples.sort()
    return statistics.median(samples) / 1000, percentile(samples, 0.9) / 1000


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="short streams, N = 4…8")
    parser.add_argument("--passes", type=int, default=5, help="timed passes over each stream")
    args = parser.parse_args(argv)
    length = 2_000 if args.quick else 10_000
    max_n = 8 if args.quick else 12
    passes = 2 if args.quick else args.passes

    print(f"# reaction benchmark — {machine()}")
    missing = "NOT installed (pip install -e '.[bench]'; dict baseline only)"
    print(f"# py_trees: {'installed' if py_trees else missing}")
    overhead = timer_overhead()
    print(f"# timer overhead {overhead:.0f} ns (subtracted); {passes} timed passes of "
          f"{length} instants after one warm-up pass; µs = median (p90)")

    cases = [("ABRO", ABRO, ("A", "B", "R"), {"A": .25, "B": .25, "R": .05},
              (lambda: pt_abro()) if py_trees else None)]
    cases.append(("Seq200", sequential(200), ("A", "B", "C"), {"A": .5, "B": .5, "C": .5},
                  (lambda: pt_sequential(200)) if py_trees else None))
    for n in range(4, max_n + 1):
        names = tuple(f"A{i}" for i in range(1, n + 1))
        cases.append((f"Par{n}", par_of_awaits(n), names, {s: 1 / n for s in names},
                      (lambda n=n: pt_par(n)) if py_trees else None))

    header = (f"{'mission':<8} {'states':>6} {'trans.':>7} {'compile':>8} | "
              f"{'ORCCAD µs/reaction':>19} {'lean µs':>15} {'react/lean':>10} | "
              f"{'py_trees µs/tick':>17} {'tree':>5} "
              f"{'ticked':>6} {'µs/node':>7} | {'ratio':>6}")
    print()
    print(header)
    print("-" * len(header))
    rows = []
    for index, (name, source, inputs, probs, make_tree) in enumerate(cases):
        start = time.perf_counter()
        automaton = compile_source(source)
        compile_s = time.perf_counter() - start
        instants = stream(inputs, probs, length, seed=1992 + index)
        ours = OrccadRunner(automaton)
        expected = ours.outputs(instants)
        ours.time(instants, 1, overhead)  # warm-up
        med, p90 = stats(ours.time(instants, passes, overhead))
        ours.time(instants, 1, overhead, lean=True)  # warm-up
        lmed, lp90 = stats(ours.time(instants, passes, overhead, lean=True))
        line = (f"{name:<8} {automaton.state_count:>6} {automaton.transition_count:>7} "
                f"{compile_s:>7.2f}s | {med:>8.2f} ({p90:>6.2f})   {lmed:>6.2f} ({lp90:>5.2f}) "
                f"{med / lmed:>9.1f}× |")
        row = dict(name=name, states=automaton.state_count,
                   transitions=automaton.transition_count, compile_s=compile_s,
                   med=med, p90=p90, lean=lmed)
        if make_tree is not None:
            runner = PyTreesRunner(make_tree())
            got, ticked = runner.outputs(instants)
            if got != expected:
                bad = next(i for i, (a, b) in enumerate(zip(got, expected)) if a != b)
                print(f"{name}: py_trees tree is NOT equivalent at instant {bad}: "
                      f"{got[bad]!r} vs {expected[bad]!r}")
                return 1
            runner.time(instants, 1, overhead)  # warm-up
            pmed, pp90 = stats(runner.time(instants, passes, overhead))
            ratio = pmed / med
            line += (f" {pmed:>7.2f} ({pmed and pp90:>6.2f}) {runner.size:>5} "
                     f"{ticked:>6.1f} {pmed / ticked:>7.2f} | {ratio:>5.1f}×")
            row.update(pt_med=pmed, pt_p90=pp90, size=runner.size, ticked=ticked, ratio=ratio)
        print(line, flush=True)
        rows.append(row)

    print()
    print("outputs of every instant identical between ORCCAD and the py_trees tree: yes")
    floor = stream(("A", "B", "R"), {"A": .25, "B": .25, "R": .05}, length, seed=1992)
    if dict_abro_outputs(floor) != OrccadRunner(compile_source(ABRO)).outputs(floor):
        print("the dict-based ABRO disagrees with the compiled one")
        return 1
    dict_abro_time(floor, 1, overhead)
    dmed, dp90 = stats(dict_abro_time(floor, passes, overhead))
    abro = rows[0]
    print(f"plain-Python floor: hand-written dict ABRO {dmed:.2f} µs ({dp90:.2f}) per "
          f"reaction; ORCCAD ABRO / floor = {abro['med'] / dmed:.1f}×")

    print()
    ok = abro["med"] <= 10.0
    print(f"target: median ABRO reaction ≤ 10 µs: {abro['med']:.2f} µs — "
          f"{'MET' if ok else 'MISSED'}")
    lean_ok = abro["lean"] <= 0.5
    print(f"target: median ABRO reaction on the lean path (Reactor.step) ≤ 0.5 µs: "
          f"{abro['lean']:.2f} µs, {abro['med'] / abro['lean']:.1f}× faster than react with its "
          f"Reaction record — {'MET' if lean_ok else 'MISSED'}")
    ok = ok and lean_ok
    if py_trees is not None:
        slower = [r["name"] for r in rows if r["ratio"] < 1.0]
        worst = min(rows, key=lambda r: r["ratio"])
        print(f"target: faster than py_trees on every tree (> 1 node): "
              f"{'MET' if not slower else 'MISSED on ' + ', '.join(slower)} "
              f"(smallest ratio {worst['ratio']:.1f}× on {worst['name']})")
        ok = ok and not slower
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
