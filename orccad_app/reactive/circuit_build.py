"""The circuit of a prepared program (:mod:`.circuit`): the walks of :mod:`.circuit_walk`
iterated to the signals' least fixpoint, then the registers' next values, the outputs and the
constraints of exact data tests."""

from __future__ import annotations

from orccad_app.reactive import ir
from orccad_app.reactive.prepare import PAUSE, PRESENT, SUSPEND, Prepared
from orccad_app.reactive.bdd import Manager, Node
from orccad_app.reactive.circuit_data import WIDTH
from orccad_app.reactive.circuit import (BOOT, FAILED_BEFORE, TERM, Circuit,
                                         Rail, counter_bit, data_var, input_var, next_name,
                                         pre_bit, register)
from orccad_app.reactive.circuit_walk import Walk, merge_codes

__all__ = ["build_circuit", "MAX_FIXPOINT_WALKS"]

#: Walks allowed to reach the signals' fixpoint (each decides at least one more status).
MAX_FIXPOINT_WALKS = 2_000


# --------------------------------------------------------------------------- building

def _declare(m: Manager, prep: Prepared, tracked: tuple[ir.VarDecl, ...]
             ) -> tuple[list[str], list[str], list[str]]:
    """Declare the variables in program order: each register beside its next copy, each
    input and data test at its first test."""
    registers: list[str] = []
    inputs: list[str] = []
    data: list[str] = []

    def reg(name: str) -> None:
        m.declare(name)
        m.declare(next_name(name))
        registers.append(name)

    for name in (BOOT, TERM, FAILED_BEFORE):
        reg(name)
    for k in range(len(tracked)):
        for bit in range(WIDTH):
            reg(counter_bit(k, bit))
    program = prep.program

    def tests(test: ir.Test) -> None:
        if isinstance(test, ir.SigRef) and test.signal.kind == ir.INPUT:
            name = input_var(program.inputs.index(test.signal))
            if not m.has(name):
                m.declare(name)
                inputs.append(name)
        elif isinstance(test, ir.DataTest):
            name = data_var(prep.data_test_index[id(test)])
            if not m.has(name):
                m.declare(name)
                data.append(name)
        elif isinstance(test, ir.PreRef):
            name = pre_bit(prep.pre_signals.index(test.signal))
            if not m.has(name):
                reg(name)
        elif isinstance(test, ir.SigNot):
            tests(test.operand)
        elif isinstance(test, (ir.SigAnd, ir.SigOr)):
            tests(test.left)
            tests(test.right)

    stack = [prep.root]
    while stack:
        node = stack.pop()
        if node.kind == PAUSE:
            reg(register(node.pid))
        elif node.kind in (PRESENT, SUSPEND):
            tests(node.src.test)
        stack.extend(reversed(node.children))
    for k in range(len(prep.pre_signals)):
        if not m.has(pre_bit(k)):
            reg(pre_bit(k))
    for index in range(len(program.inputs)):
        name = input_var(index)
        if not m.has(name):
            m.declare(name)
            inputs.append(name)
    for number in range(len(prep.data_tests)):
        name = data_var(number)
        if not m.has(name):
            m.declare(name)
            data.append(name)
    return registers, inputs, data


def _relations(m: Manager, program: ir.Program) -> Node:
    """Where the inputs satisfy every ``relation`` of the program."""
    result = m.true
    for relation in program.relations:
        bits = [m.var(input_var(program.inputs.index(s))) for s in relation.signals]
        if relation.kind == "#":
            for i, a in enumerate(bits):
                for b in bits[i + 1:]:
                    result &= ~(a & b)
        else:
            result &= ~bits[0] | bits[1]
    return result


def build_circuit(prep: Prepared, manager: Manager | None = None,
                  tracked: tuple[ir.VarDecl, ...] = ()) -> Circuit:
    """The circuit of ``prep``: its walks iterated to the signals' fixpoint; ``tracked``: the
    variables kept exactly (:mod:`.circuit_data`), the other data abstracted."""
    m = manager or Manager()
    registers, inputs, data = _declare(m, prep, tracked)
    circuit = Circuit(prep, m, registers, inputs, data, tracked=tracked)
    circuit.relations = _relations(m, prep.program)
    boot, term = m.var(BOOT), m.var(TERM)
    running = ~term
    env: dict = {}
    while True:
        walk = Walk(circuit, env)
        surface = boot & running
        depth_act = ~boot & running
        codes = walk.go(prep.root, False, (surface, surface), {})
        merge_codes(codes, walk.go(prep.root, True, (depth_act, depth_act), {}))
        circuit.walks += 1
        circuit.activation_rounds.append({a.visit: a.sure for a in walk.activations})
        changed = False
        keys = set(walk.can) | set(env) | walk.tested
        new_env = {}
        for key in keys:
            present = walk.must.get(key, m.false)
            absent = ~walk.can.get(key, m.false)
            new_env[key] = (present, absent)
            old = env.get(key)
            if old is None or old[0] != present or old[1] != absent:
                changed = True
        env = new_env
        if not changed:
            break
        if circuit.walks > MAX_FIXPOINT_WALKS:  # pragma: no cover - monotone, bounded by keys
            break
    _outputs(circuit, walk, codes, env)
    return circuit


def _outputs(circuit: Circuit, walk: Walk, codes: dict[int, Rail], env: dict) -> None:
    m = circuit.manager
    prep = circuit.prep
    program = prep.program
    boot, term = m.var(BOOT), m.var(TERM)
    running = ~term
    code0 = codes.get(0, (m.false, m.false))[0]
    circuit.code0 = code0
    for decl in (*program.outputs, program.failed, program.aborted):
        if decl is not None:
            circuit.emitted[decl] = walk.must.get(decl, m.false)
    for pid in range(len(prep.pauses)):
        circuit.next[register(pid)] = walk.next.get(pid, m.false) & running
    circuit.next[BOOT] = m.false
    circuit.next[TERM] = term | code0
    bad = m.false
    for decl in (program.failed, program.aborted):
        if decl is not None:
            bad |= circuit.emitted[decl]
    circuit.next[FAILED_BEFORE] = m.var(FAILED_BEFORE) | bad
    for k, decl in enumerate(prep.pre_signals):
        name = pre_bit(k)
        if decl.kind == ir.INPUT:
            present = m.var(input_var(program.inputs.index(decl)))
        elif decl.kind == ir.LOCAL:
            fresh = walk.fresh.get(decl, m.false)
            present = ((fresh & walk.must.get((decl, False), m.false))
                       | (~fresh & walk.must.get((decl, True), m.false)))
            suspended = _suspended(circuit, walk, decl)
            present = (suspended & m.var(name)) | (~suspended & present)
        else:
            present = walk.must.get(decl, m.false)
        circuit.next[name] = present & running & ~code0
    circuit.evaluated = walk.evaluated
    for k, var in enumerate(circuit.tracked):
        for bit, value in enumerate(walk.values[var]):
            circuit.next[counter_bit(k, bit)] = value & running & ~code0
    circuit.overflow = walk.arithmetic.overflow
    circuit.relations &= walk.constraints
    circuit.activations = walk.activations
    circuit.undecided = [(where, loc, name) for where, loc, name in walk.undecided
                         if where != m.false]
    del boot


def _suspended(circuit: Circuit, walk: Walk, decl: ir.SignalDecl) -> Node:
    """Where the declaration of local ``decl`` is alive inside a suspend frozen in the
    instant (its ``pre`` then keeps the value of the last instant its scope ran)."""
    m = circuit.manager
    result = m.false
    for index, lo, hi in circuit.prep.local_nodes.get(decl, ()):
        if lo == hi:
            continue
        alive = circuit.selected(lo, hi)
        for frozen, where in walk.frozen:
            if frozen.index < index and frozen.lo <= lo and hi <= frozen.hi:
                result |= alive & where
    return result
