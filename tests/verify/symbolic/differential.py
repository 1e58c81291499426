"""The circuit against the explicit engine, transition by transition (a test helper).

Every state the explicit compiler explores (:mod:`orccad_app.reactive.compiler`), every
path of its reaction tree (inputs tested, data test outcomes): the circuit's next registers
and outputs at that point must be the engine's target state and outputs.
"""

from __future__ import annotations

from collections import deque

from orccad_app.reactive.automaton import TERMINAL, DataBranch, InputTest, Leaf
from orccad_app.reactive.compiler import DEFAULT_MAX_STATES, _Explorer, _targets
from orccad_app.reactive.engine import BOOT
from orccad_app.reactive.prepare import Prepared
from orccad_app.reactive.circuit_build import build_circuit
from orccad_app.reactive.circuit import (BOOT as BOOT_REG, FAILED_BEFORE, TERM,
                                                data_var, input_var, pre_bit,
                                                register)


def _trees(prep: Prepared) -> dict:
    explorer = _Explorer(prep, DEFAULT_MAX_STATES)
    trees = {}
    queue, seen = deque([BOOT]), {BOOT}
    while queue:
        state = queue.popleft()
        trees[state] = tree = explorer.tree(state)
        for target in _targets(tree):
            if target not in seen:
                seen.add(target)
                queue.append(target)
    return trees


def _paths(tree, inputs=(), data=()):
    if isinstance(tree, Leaf):
        yield dict(inputs), dict(data), tree
    elif isinstance(tree, InputTest):
        yield from _paths(tree.then, inputs + ((tree.signal, True),), data)
        yield from _paths(tree.orelse, inputs + ((tree.signal, False),), data)
    elif isinstance(tree, DataBranch):
        yield from _paths(tree.then, inputs, data + ((tree.number, True),))
        yield from _paths(tree.orelse, inputs, data + ((tree.number, False),))
    else:
        yield from _paths(tree.next, inputs, data)


def _registers(prep: Prepared, key) -> dict[str, bool]:
    if key is BOOT:
        return {BOOT_REG: True}
    if key == TERMINAL:
        return {TERM: True}
    return {register(p) if p < prep.pre_base else pre_bit(p - prep.pre_base): True for p in key}


def mismatches(prep: Prepared) -> tuple[int, list[str]]:
    """(transitions compared, descriptions of those where the circuit and engine differ)."""
    trees = _trees(prep)  # first: the explicit compiler may refuse the program
    circuit = build_circuit(prep)
    try:
        return _compare(prep, circuit, trees)
    finally:
        circuit.manager.release(circuit)


def _compare(prep: Prepared, circuit, trees: dict) -> tuple[int, list[str]]:
    m = circuit.manager
    program = prep.program
    compared, found = 0, []
    for key, tree in trees.items():
        if key == TERMINAL:
            continue
        current = _registers(prep, key)
        for inputs, data, leaf in _paths(tree):
            point = {r: current.get(r, False) for r in circuit.registers}
            point[FAILED_BEFORE] = False
            point.update({input_var(i): inputs.get(d, False) for i, d in enumerate(program.inputs)})
            point.update({data_var(n): data.get(n, False) for n in range(len(prep.data_tests))})
            values = {k: (m.true if v else m.false) for k, v in point.items() if m.has(k)}

            def holds(node, values=values):
                return m.bdd.let(values, node) == m.true

            if program.relations and not holds(circuit.relations):
                continue
            compared += 1
            expected = _registers(prep, leaf.target)
            got = {r for r in circuit.registers if r not in (BOOT_REG, FAILED_BEFORE)
                   and holds(circuit.next[r])}
            want = {r for r, on in expected.items() if on}
            emitted = {d.name for d in program.outputs if holds(circuit.emitted[d])}
            if got != want or emitted != {d.name for d in leaf.emitted}:
                found.append(f"from {key} with {sorted(d.name for d, v in inputs.items() if v)}"
                             f", data {data}: engine {sorted(want)} {sorted(d.name for d in leaf.emitted)}"
                             f", circuit {sorted(got)} {sorted(emitted)}")
    return compared, found
