"""C99 for a program's circuit: the step computes the registers and outputs from the BDDs.

The explicit generator (:mod:`.generate`) writes every state's reaction tree: its size is the
product of what parallel branches test. This one writes the circuit
(:mod:`orccad_app.reactive.circuit`): the memory holds one register per pause and ``pre`` bit
(``m->reg``), and the step

1. starts as the explicit step does (clock, relations, ``pre`` values, input values);
2. runs the data events in the static order of :mod:`.circuit_schedule`, each under its
   activation (a BDD over the registers, the inputs and the data tests before it): data
   tests set ``t[n]``, actions are the same C functions as the explicit generator's;
3. computes the outputs, the instant's status and every register's next value, then stores
   the registers.

A BDD node is one line ``x[k] = v ? hi : lo;`` (complemented edges as ``!``), written once
(shared by every function that reaches it) just before the first event or output that needs
it: the C grows with the BDDs, which are local to each parallel branch. No state numbers
exist: ``out->state`` and ``m->state`` stay 0, and ``PREFIX_phase`` reads the registers of the
Robot-Tasks' marked regions.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import cast

from orccad_app.codegen.cexpr import ExprWriter, StringTable, c_comment
from orccad_app.codegen.circuit_reach import reachable, simplify
from orccad_app.codegen.circuit_schedule import Event, NotStatic, schedule
from orccad_app.codegen.errors import ErrorKind, ErrorTable
from orccad_app.codegen.generate import (
    STATUS_CODES, CProgram, _copy, _function, _places, _reason_places, _reset, _strings,
    _tables, _used, step_epilogue, step_prologue,
)
from orccad_app.codegen.header import header_text
from orccad_app.codegen.helpers import helpers_for
from orccad_app.codegen.interface import Interface
from orccad_app.codegen.names import own_macros
from orccad_app.codegen.reaction import ActionRef, Graph
from orccad_app.codegen.sites import SiteInfo
from orccad_app.codegen.static_types import CodegenError, CType, infer
from orccad_app.reactive import ir
from orccad_app.reactive.status import Status
from orccad_app.reactive.bdd import Node
from orccad_app.reactive.circuit import TERM, Circuit, register
from orccad_app.reactive.circuit_build import build_circuit
from orccad_app.reactive.prepare import Prepared, prepare
from orccad_app.reactive.reads import made
from orccad_app.robottask.labels import Phase, PhaseLabel, RtLabel
from orccad_app.robottask.signals import SignalRoles

__all__ = ["generate_circuit", "circuit_of", "GATES_PER_FUNCTION"]

#: node definitions per gate function (``static void gN``)
GATES_PER_FUNCTION = 200


@dataclass(frozen=True)
class _Gate:
    """A line defining a BDD node's wire."""

    text: str


@dataclass(frozen=True)
class _Shape:
    """What the shared parts of the generator read of an automaton."""

    program: ir.Program
    state_count: int = 1
    initial: int = 0


def circuit_of(program: ir.Program) -> Circuit:
    """The circuit of ``program`` as a run sees it (a second valued emission without
    ``combine`` fails at run time, as ``orccad react`` and the explicit C)."""
    prep = prepare(program)
    prep.defer_double_emissions = True
    return build_circuit(prep)


def generate_circuit(circuit: Circuit, prefix: str, *, roles: SignalRoles | None = None,
                     sites: tuple[SiteInfo, ...] = (),
                     hints: dict[ir.SignalDecl, CType] | None = None, origin: str = "",
                     note: tuple[str, ...] = ()) -> CProgram:
    """The C of ``circuit`` (see :func:`.generate.generate` for the parameters; ``note``:
    header lines saying why this generator). Raises
    :class:`~.circuit_schedule.NotStatic` when its events have no static order and
    :class:`~.static_types.CodegenError` for what has no C translation (without the
    traceback of the generation: its frames hold BDD nodes, which must not outlive the
    manager)."""
    try:
        return _generate(circuit, prefix, roles, sites, hints, origin, note)
    except (NotStatic, CodegenError) as error:
        failure = error
    raise failure.with_traceback(None)


def _generate(circuit: Circuit, prefix: str, roles: SignalRoles | None,
              sites: tuple[SiteInfo, ...], hints: dict[ir.SignalDecl, CType] | None,
              origin: str, note: tuple[str, ...]) -> CProgram:
    prep = circuit.prep
    program = prep.program
    care = reachable(circuit)
    events = schedule(circuit, care)
    plan = _Plan(prep, events)
    signals = (*program.inputs, *program.outputs)
    tests = [prep.data_tests[n].expr for n in plan.tests]
    graph = Graph([], [], plan.actions, plan.tests)
    types = infer([(a.kind, a.target, a.expr) for a in plan.actions], tests, signals, hints)
    strings = StringTable(_strings(graph, tests, signals, types))
    places = _places(types, graph, tests)
    errors = ErrorTable()
    interface = Interface.make(program.inputs, program.outputs, types.places, roles,
                               own_macros(prefix))
    reason = _reason_places(program, places)
    writer = ExprWriter(types, places, errors, strings)
    functions = []
    for number, action in enumerate(plan.actions):
        lines = _used(("m",), writer.action(action.kind, action.target, action.expr))
        functions.append(_function(f"static int a{number}({prefix}_mem *m)", lines))
    for number in plan.tests:
        lines = _used(("m", "r"), writer.test(prep.data_tests[number].expr))
        functions.append(_function(f"static int d{number}({prefix}_mem *m, bool *r)", lines))
    relations = [(r, errors.code(ErrorKind.RELATION, r.loc,
                                 f"these inputs violate 'relation {r.text}' (declared at "
                                 f"{r.loc})")) for r in program.relations]
    registers = len(circuit.registers)
    writer_step = _Step(circuit, plan, interface, places, care)
    step = writer_step.text(prefix, errors, relations, reason)
    functions += writer_step.gates
    shape = _Shape(program)
    form = (f" * The circuit of mission {c_comment(program.name)} ({registers} registers, "
            f"{len(events)} data events), as C99.")
    memory = (f"    unsigned char reg[{registers}]; /* the registers: boot, terminated, "
              "failed before, then one per pause and pre bit */",)
    header = header_text(prefix, shape, interface, places, strings, errors,
                         sites, origin, form=form, note=note, memory=memory)
    body = "\n\n".join(functions + [step])
    reset = _reset(prefix, shape, places, strings,
                   (f"{{ int i; for (i = 0; i < {registers}; ++i) m->reg[i] = 0; }}",
                    "m->reg[0] = 1; /* boot */"))
    source = "\n".join([
        f"/* {prefix}.c: generated by orccad codegen{c_comment(origin)} (circuit). "
        "Do not edit. */",
        f'#include "{prefix}.h"',
        "",
        helpers_for(body),
        "",
        _tables(prefix, interface, strings, errors, sites, [], 0,
                phase_function=_phase_function(prefix, circuit, len(sites))),
        "",
        reset,
        "",
        body,
        "",
    ])
    return CProgram(prefix, header, source, interface, strings, errors, types, graph,
                    generator="circuit")


# --------------------------------------------------------------------------- the actions

class _Plan:
    """The distinct data actions of the events and the C of each event's action(s)."""

    def __init__(self, prep: Prepared, events: list[Event]):
        self.prep = prep
        self.events = events
        self.actions: list[ActionRef] = []
        self._ids: dict[tuple, int] = {}
        tests: dict[int, None] = {}
        emitters: dict = {}
        for event in events:
            a = event.activation
            if a.kind == "test":
                tests.setdefault(cast(int, a.target))  # a test's target: its number
            elif a.kind == "emit":
                emitters.setdefault(a.key, []).append(a)
        self.tests = list(tests)
        self.shared_tests = {n for n in tests
                             if sum(e.activation.kind == "test" and e.activation.target == n
                                    for e in events) > 1}
        #: the incarnations with several emissions: a local int names the first one run
        self.multiple = {key: number for number, key in
                         enumerate(k for k, found in emitters.items() if len(found) > 1)}
        self.order = {id(a): index + 1 for found in emitters.values()
                      for index, a in enumerate(found)}
        self.emitters = emitters
        #: the C of each event (every distinct action numbered before any is written)
        self.codes = [self._code(event) for event in events]

    def action(self, kind: str, target: object, expr: ir.Expr) -> int:
        key = (kind, id(target), id(expr))
        number = self._ids.get(key)
        if number is None:
            number = self._ids[key] = len(self.actions)
            self.actions.append(ActionRef(kind, target, expr))
        return number

    def _code(self, event: Event) -> list[str]:
        """The C that runs ``event`` (its activation holding)."""
        a = event.activation
        prep = self.prep
        if a.kind == "test":
            lines = [f"if ((e = d{a.target}(m, &b)) != 0) return e;", f"t[{a.target}] = b;"]
            if a.target in self.shared_tests:
                return [f"if (!v[{a.target}]) {{", *("    " + line for line in lines),
                        f"    v[{a.target}] = true;", "}"]
            return lines
        if a.kind == "assign":
            return [_call(self.action("assign", a.target, cast(ir.Expr, a.expr)))]
        target = cast(ir.SignalDecl, a.target)  # an emission's or a new incarnation's signal
        loc = a.node.src.loc
        if a.kind == "init":
            value = made(prep, ("init", target), lambda: ir.Const(
                ir.NO_VALUE if target.init is None else target.init, loc))
            return [_call(self.action("emit", target, value))]
        assert a.expr is not None
        plain = _call(self.action("emit", target, a.expr))
        if a.key not in self.multiple:
            return [plain]
        flag = f"em{self.multiple[a.key]}"
        mine = self.order[id(a)]
        if mine == 1:  # the first in the walk: no other emission of it ran before
            return [plain, f"{flag} = 1;"]
        lines = [f"if ({flag} == 0) {{ {plain} }}"]
        expr = a.expr
        if target.combine is not None:
            combined = made(prep, ("combine", id(expr)), lambda: ir.Binary(
                target.combine, ir.SigValue(target, loc), expr, loc))
            lines.append(f"else {{ {_call(self.action('emit', target, combined))} }}")
        else:
            for other in self.emitters[a.key]:
                if self.order[id(other)] >= mine:
                    break
                first = other.node.src.loc
                message = (f"signal {target.name} is emitted twice in one instant (first at "
                           f"{first}): declare how its values combine, e.g. "
                           f"'output {target.name} : {target.type} combine +;'")
                fault = made(prep, ("fault", id(expr), id(other.expr)),
                             lambda message=message: ir.Fault(message, loc))
                lines.append(f"else if ({flag} == {self.order[id(other)]}) "
                             f"{{ {_call(self.action('emit', target, fault))} }}")
        lines.append(f"{flag} = {mine};")
        return lines


def _call(number: int) -> str:
    return f"if ((e = a{number}(m)) != 0) return e;"


# --------------------------------------------------------------------------- the step

class _Step:
    """The step function: BDD nodes written as the events and outputs need them."""

    def __init__(self, circuit: Circuit, plan: _Plan, interface: Interface, places,
                 care: Node):
        self.c = circuit
        self.care = care
        self.m = circuit.manager
        self.plan = plan
        self.interface = interface
        self.places = places
        self.slot: dict[int, int] = {}       # node (its address in CUDD) -> its wire
        self.held: list[Node] = []            # the nodes of the slots, kept alive
        self.wires = 0                        # wires x[] written so far
        #: the data tests (numbers) a wire reads: written again once they are evaluated
        self.reads: dict[int, frozenset[int]] = {}
        self.tests_read = {name: frozenset({int(name[1:])}) for name in circuit.data}
        self.lines: list = []               # C lines, and _Gate lines (node definitions)
        self.gates: list[str] = []          # the functions computing runs of nodes
        self.register_index = {name: i for i, name in enumerate(circuit.registers)}
        program = circuit.prep.program
        fields = {s.decl: s.field for s in interface.inputs}
        self.input_field = {f"i{i}": fields[decl] for i, decl in enumerate(program.inputs)}

    def var(self, name: str) -> str:
        index = self.register_index.get(name)
        if index is not None:
            return f"m->reg[{index}]"
        if name.startswith("i"):
            return f"in->{self.input_field[name]}"
        return f"t[{int(name[1:])}]"

    def wire(self, f: Node) -> str:
        """The C of ``f`` as the step needs it: simplified where the registers are not
        reachable (:func:`.circuit_reach.simplify`)."""
        return self.ref(simplify(f, self.care))

    def ref(self, u: Node) -> str:
        """The C of ``u`` (its nodes written first)."""
        if u == self.m.true:
            return "1"
        if u == self.m.false:
            return "0"
        regular = ~u if u.negated else u
        self._define(regular)
        text = f"x[{self.slot[int(regular)]}]"
        return "!" + text if u.negated else text

    def _define(self, root: Node) -> None:
        stack = [(root, False)]
        while stack:
            u, ready = stack.pop()
            if int(u) in self.slot:
                continue
            low, high = u.low, u.high
            if not ready:
                stack.append((u, True))
                for child in (low, high):
                    regular = ~child if child.negated else child
                    if regular.var is not None and int(regular) not in self.slot:
                        stack.append((regular, False))
                continue
            v = self.var(u.var)
            hi, lo = self.ref(high), self.ref(low)
            if hi == "1":
                text = f"{v} || {lo}" if lo != "0" else v
            elif hi == "0":
                text = f"!{v} && {lo}" if lo != "1" else f"!{v}"
            elif lo == "0":
                text = f"{v} && {hi}"
            elif lo == "1":
                text = f"!{v} || {hi}"
            else:
                text = f"{v} ? {hi} : {lo}"
            number = self.slot[int(u)] = self.wires
            self.wires += 1
            tests = self.tests_read.get(u.var, frozenset())
            for child in (low, high):
                key = int(~child if child.negated else child)
                tests = tests | self.reads.get(key, frozenset())
            if tests:
                self.reads[int(u)] = tests
            # its node stays allocated while the step is written: a temporary BDD freed
            # could give its address to another node, which ``slot`` would then name
            self.held.append(u)
            self.lines.append(_Gate(f"x[{number}] = {text};"))

    def _forget(self, number: int) -> None:
        """Data test ``number`` may just have been evaluated: a wire computed before from
        its (then unset) outcome is written again when next needed. (A function need not
        depend on a test where it is not yet evaluated, but a node it shares with one that
        does, computed early, holds the outcome's old value.)"""
        for key in [k for k, tests in self.reads.items() if number in tests]:
            del self.reads[key]
            self.slot.pop(key, None)

    def _grouped(self, prefix: str) -> list[str]:
        """The step's lines, each run of node definitions moved into a function of at most
        :data:`GATES_PER_FUNCTION` lines (a compiler optimizes many small functions much
        faster than one function of thousands of statements)."""
        out: list[str] = []
        run: list[str] = []
        tests = bool(self.plan.tests)
        signature = (f"static void g{{}}(const {prefix}_mem *m, const {prefix}_in *in, "
                     + ("const bool *t, " if tests else "") + "unsigned char *x)")
        call = "g{}(m, in, " + ("t, " if tests else "") + "x);"

        def flush() -> None:
            if run:
                number = len(self.gates)
                text = "\n".join(run)
                unused = [f"(void){name};" for name in ("m", "in", "t")
                          if (name != "t" or tests) and not re.search(rf"\b{name}\b", text)]
                self.gates.append(_function(signature.format(number), unused + run))
                out.append(call.format(number))
                run.clear()

        for line in self.lines:
            if isinstance(line, _Gate):
                run.append(line.text)
                if len(run) >= GATES_PER_FUNCTION:
                    flush()
            else:
                flush()
                out.append(line)
        flush()
        return out

    def text(self, prefix: str, errors: ErrorTable, relations, reason) -> str:
        c, plan = self.c, self.plan
        program = c.prep.program
        for event, code in zip(plan.events, plan.codes):
            condition = self.wire(event.activation.sure)
            if condition == "1":
                self.lines += code
            else:
                self.lines.append(f"if ({condition}) {{")
                self.lines += ["    " + line for line in code]
                self.lines.append("}")
            if event.activation.kind == "test":
                self._forget(cast(int, event.activation.target))
        emitted = {}
        for signal in self.interface.outputs:
            emitted[signal.decl] = self.wire(c.emitted.get(signal.decl, self.m.false))
        status = []
        for value, decl in ((Status.ABORTED, program.aborted), (Status.FAILED, program.failed)):
            if decl is not None:
                status.append((value, self.wire(c.emitted.get(decl, self.m.false))))
        code0 = self.wire(c.code0)
        nexts = [self.wire(c.next[name]) for name in c.registers]
        body: list[str] = []
        if plan.actions or plan.tests:
            body.append("int e;")
        if plan.tests:
            body += ["bool b;", f"bool t[{max(plan.tests) + 1}] = {{0}};"]
            if plan.shared_tests:
                body.append(f"bool v[{max(plan.tests) + 1}] = {{0}};")
        body += [f"int em{n} = 0;" for n in plan.multiple.values()]
        if self.wires:
            body.append(f"unsigned char x[{self.wires}];")
        body += [f"unsigned char nx[{len(c.registers)}];", "int i;", "int st;", "(void)in;"]
        body += step_prologue(self.interface, self.places, errors, relations)
        body += [f"if (m->reg[0] > 1 || m->reg[1] > 1) return {errors.state};"]
        body += self._grouped(prefix)
        for signal in self.interface.outputs:
            body.append(f"out->{signal.field} = {emitted[signal.decl]};")
            place = self.places.values.get(signal.decl)
            if signal.ctype is not None and place is not None:
                copy = " ".join(_copy(f"out->{signal.value_field}", place.value, place.ctype))
                body.append(f"if (out->{signal.field}) {{ {copy} }}")
        term = f"m->reg[{self.register_index[TERM]}]"
        chain = "".join(f"{cond} ? {STATUS_CODES[value]} : " for value, cond in status)
        body.append(f"st = {chain}({term} || {code0}) ? {STATUS_CODES[Status.DONE]} : "
                    f"{STATUS_CODES[Status.RUNNING]};")
        body += [f"nx[{i}] = {text};" for i, text in enumerate(nexts)]
        body += [f"for (i = 0; i < {len(c.registers)}; ++i) m->reg[i] = nx[i];",
                 "out->status = st;", "out->state = 0;"]
        body += step_epilogue(prefix, reason)
        return _function(f"int {prefix}_step({prefix}_mem *m, int64_t clock_ns, "
                         f"const {prefix}_in *in, {prefix}_out *out)", body)


def _phase_function(prefix: str, circuit: Circuit, site_count: int) -> str:
    """``PREFIX_phase``: the highest phase of the site's marked regions holding a set
    register (as the explicit automaton's labels: :func:`.generate._phases`)."""
    index = {name: i for i, name in enumerate(circuit.registers)}
    cases: dict[int, list[str]] = {}
    for label, lo, hi in circuit.prep.marks:
        if isinstance(label, PhaseLabel) and label.site < site_count:
            site, phase = label.site, int(label.phase)
        elif isinstance(label, RtLabel) and label.site < site_count:
            site, phase = label.site, int(Phase.SYNCHRONIZING)
        else:
            continue
        held = [f"m->reg[{index[register(p)]}]" for p in range(lo, hi)
                if register(p) in index]
        if held:
            cases.setdefault(site, []).append(
                f"    if (p < {phase} && ({' || '.join(held)})) p = {phase};")
    if not cases:
        return _function(f"int {prefix}_phase(const {prefix}_mem *m, int site)",
                         ["(void)m;", "(void)site;", "return 0;"])
    body = ["int p = 0;", "switch (site) {"]
    for site in sorted(cases):
        body += [f"case {site}:", *cases[site], "    break;"]
    body += ["default:", "    break;", "}", "return p;"]
    return _function(f"int {prefix}_phase(const {prefix}_mem *m, int site)", body)
