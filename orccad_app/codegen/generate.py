"""C99 for a compiled automaton: ``PREFIX.h`` (the documented interface) and ``PREFIX.c``.

:func:`generate` takes the automaton ``orccad check`` proves (the full, minimized one) and
writes it as a reentrant C step function over caller-owned memory::

    void PREFIX_reset(PREFIX_mem *m);
    int  PREFIX_step(PREFIX_mem *m, int64_t clock_ns, const PREFIX_in *in, PREFIX_out *out);

One step is one instant of :meth:`orccad_app.reactive.runtime.Reactor.step`, in the same
order: the clock (it may not go back), the declared relations, the ``pre(?S)`` values, the
input values, then the state's reaction tree (:mod:`.reaction`) with its data actions and
tests (:mod:`.cexpr`). It returns the mission's status (``PREFIX_RUNNING``…, sticky once
``failed`` or ``aborted`` as in the runtime) or a negative error code whose entry in
``PREFIX_errors`` is the located error the Python runtime raises (:mod:`.errors`).
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import cast

from orccad_app.codegen.cexpr import (ExprWriter, Place, Places, StringTable, c_comment, c_literal,
                                      c_string)
from orccad_app.codegen.errors import ErrorKind, ErrorTable
from orccad_app.codegen.helpers import helpers_for
from orccad_app.codegen.header import AutomatonShape, header_text
from orccad_app.codegen.interface import ROLE_CODES, Interface
from orccad_app.codegen.names import c_identifier, own_macros
from orccad_app.codegen.reaction import Graph, intern
from orccad_app.codegen.sites import SiteInfo, phase_columns, site_tables
from orccad_app.codegen.static_types import CType, CodegenError, Kind, TypeTable, infer
from orccad_app.reactive import ir
from orccad_app.reactive.automaton import Automaton
from orccad_app.reactive.status import Status
from orccad_app.robottask.labels import Phase, PhaseLabel, RtLabel
from orccad_app.robottask.signals import SignalRoles

__all__ = ["CProgram", "generate", "STATUS_CODES"]

STATUS_CODES = {Status.RUNNING: 0, Status.DONE: 1, Status.FAILED: 2, Status.ABORTED: 3}


@dataclass(frozen=True)
class CProgram:
    """The generated files and what a driver (``PREFIX_main.c``, tests) needs to know."""

    prefix: str
    header: str
    source: str
    interface: Interface
    strings: StringTable
    errors: ErrorTable
    types: TypeTable
    graph: Graph
    #: which generator wrote it: ``explicit`` (the automaton) or ``circuit`` (:mod:`.circuit`)
    generator: str = "explicit"

    @property
    def files(self) -> dict[str, str]:
        return {f"{self.prefix}.h": self.header, f"{self.prefix}.c": self.source}


def generate(automaton: Automaton, prefix: str, *, roles: SignalRoles | None = None,
             sites: tuple[SiteInfo, ...] = (),
             hints: dict[ir.SignalDecl, CType] | None = None, origin: str = "",
             note: tuple[str, ...] = ()) -> CProgram:
    """The C of ``automaton`` with identifiers prefixed ``prefix``; ``roles``: the role of
    each generated signal, ``sites``: what each run site starts (number order,
    :mod:`.sites`),
    ``hints``: types known from elsewhere; ``origin``: what it was generated from (a
    comment; ``note``: header lines saying why this generator). Raises
    :class:`CodegenError` (located) for what has no C translation."""
    graph = intern(automaton.trees)
    program = automaton.program
    signals = (*program.inputs, *program.outputs)
    tests = [automaton.data_tests[n].expr for n in graph.tests]
    types = infer([(a.kind, a.target, a.expr) for a in graph.actions], tests, signals, hints)
    strings = StringTable(_strings(graph, tests, signals, types))
    places = _places(types, graph, tests)
    errors = ErrorTable()
    interface = Interface.make(program.inputs, program.outputs, types.places, roles,
                               own_macros(prefix))
    reason = _reason_places(program, places)
    writer = ExprWriter(types, places, errors, strings)
    functions = []
    for number, action in enumerate(graph.actions):
        body = _used(("m",), writer.action(action.kind, action.target, action.expr))
        functions.append(_function(f"static int a{number}({prefix}_mem *m)", body))
    for number in graph.tests:
        body = _used(("m", "r"), writer.test(automaton.data_tests[number].expr))
        functions.append(_function(f"static int d{number}({prefix}_mem *m, bool *r)", body))
    relations = [(r, errors.code(ErrorKind.RELATION, r.loc,
                                 f"these inputs violate 'relation {r.text}' (declared at "
                                 f"{r.loc})")) for r in program.relations]
    step = _step(prefix, automaton, graph, interface, places, errors, relations, reason)
    phases = _phases(automaton, len(sites))
    header = header_text(prefix, automaton, interface, places, strings, errors, sites, origin,
                         note=note)
    code = "\n\n".join(functions + [step])
    source = "\n".join([
        f"/* {prefix}.c: generated by orccad codegen{c_comment(origin)}. Do not edit. */",
        f'#include "{prefix}.h"',
        "",
        helpers_for(code),
        "",
        _tables(prefix, interface, strings, errors, sites, phases, automaton.state_count),
        "",
        _reset(prefix, automaton, places, strings),
        "",
        code,
        "",
    ])
    return CProgram(prefix, header, source, interface, strings, errors, types, graph)


# --------------------------------------------------------------------------- collection

def _strings(graph: Graph, tests: list[ir.Expr], signals, types: TypeTable) -> set[str]:
    found: set[str] = set()
    stack: list = [a.expr for a in graph.actions] + list(tests)
    while stack:
        expr = stack.pop()
        kind = type(expr)
        if kind is ir.Const and isinstance(expr.value, str):
            found.add(_c_text(expr.value, expr.loc))
        elif kind is ir.Unary:
            stack.append(expr.operand)
        elif kind is ir.Binary:
            stack.extend((expr.left, expr.right))
        elif kind is ir.VectorExpr:
            stack.extend(expr.items)
    for signal in signals:
        if isinstance(signal.init, str):
            found.add(_c_text(signal.init, signal.loc))
    return found


def _c_text(text: str, loc) -> str:
    """``text``, which a C string can hold (it ends at its first NUL), else a located error."""
    if "\0" in text:
        raise CodegenError("a string holding the NUL character (\\0) has no C string: C ends "
                           "a string at its first NUL", loc)
    return text


def _pre_read(graph: Graph, tests: list[ir.Expr]) -> list[ir.SignalDecl]:
    found: dict = {}
    stack: list = [a.expr for a in graph.actions] + list(tests)
    while stack:
        expr = stack.pop()
        kind = type(expr)
        if kind is ir.PreValue:
            found[expr.signal] = None
        elif kind is ir.Unary:
            stack.append(expr.operand)
        elif kind is ir.Binary:
            stack.extend((expr.left, expr.right))
        elif kind is ir.VectorExpr:
            stack.extend(expr.items)
    return list(found)


def _places(types: TypeTable, graph: Graph, tests: list[ir.Expr]) -> Places:
    places = Places()
    taken: set[str] = set()
    for number, (decl, ctype) in enumerate(types.places.items()):
        name = c_identifier(decl.name, taken)  # type: ignore[attr-defined]
        if isinstance(decl, ir.VarDecl):
            places.variables[decl] = Place(f"m->v{number}_{name}", f"m->v{number}_{name}_has",
                                           ctype)
        else:  # the type table's other places are signals
            places.values[cast(ir.SignalDecl, decl)] = Place(f"m->s{number}_{name}", f"m->s{number}_{name}_has",
                                        ctype)
    for signal in _pre_read(graph, tests):
        value = places.values.get(signal)
        if value is not None:
            base = value.value.replace("m->s", "m->p", 1)
            places.previous[signal] = Place(base, base + "_has", value.ctype)
    return places


def _reason_places(program: ir.Program, places: Places) -> dict[str, Place | None]:
    found: dict[str, Place | None] = {}
    for status, decl in ((Status.FAILED, program.failed), (Status.ABORTED, program.aborted)):
        place = places.values.get(decl) if decl is not None else None
        if place is not None and place.ctype.kind is not Kind.STRING:
            raise CodegenError(f"the {status} reason {decl.name} is not a string",  # type: ignore[union-attr]
                               decl.loc)  # type: ignore[union-attr]
        found[status] = place
    return found


def _phases(automaton: Automaton, site_count: int) -> list[list[int]]:
    rows = []
    labels = automaton.labels or tuple(frozenset() for _ in automaton.trees)
    for state_labels in labels:
        row = [0] * site_count
        for label in state_labels:  # as the mission layer reads them (MissionRun._phases)
            if isinstance(label, PhaseLabel) and label.site < site_count:
                row[label.site] = max(row[label.site], int(label.phase))
            elif isinstance(label, RtLabel) and label.site < site_count:
                row[label.site] = max(row[label.site], int(Phase.SYNCHRONIZING))
        rows.append(row)
    return rows


def _function(signature: str, body: list[str]) -> str:
    return signature + "\n{\n" + "\n".join("    " + line for line in body) + "\n}"


def _used(parameters: tuple[str, ...], body: list[str]) -> list[str]:
    """``body`` after ``(void)p;`` for each parameter it does not read (a data action that
    always fails, e.g. a second emission the inputs make, reads no memory)."""
    text = "\n".join(body)
    unused = [p for p in parameters if not re.search(rf"\b{p}\b", text)]
    return [f"(void){p};" for p in unused] + body


# --------------------------------------------------------------------------- the step

def _step(prefix: str, automaton: Automaton, graph: Graph, interface: Interface,
          places: Places, errors: ErrorTable, relations, reason) -> str:
    lines = [f"int {prefix}_step({prefix}_mem *m, int64_t clock_ns, const {prefix}_in *in, "
             f"{prefix}_out *out)", "{"]
    body: list[str] = []
    uses_e = bool(graph.actions) or bool(graph.tests)
    if uses_e:
        body.append("int e;")
    if graph.tests:
        body.append("bool b;")
    body += ["int st;", "(void)in;"]
    body += step_prologue(interface, places, errors, relations)
    body.append("switch (m->state) {")
    for state, root in enumerate(graph.roots):
        body.append(f"case {state}: goto n{root};")
    body.append(f"default: return {errors.state};")
    body.append("}")
    for number, node in enumerate(graph.nodes):
        body.append(_node(number, node, graph, interface, places))
    body += ["end:", "out->status = st;", "out->state = m->state;"]
    body += step_epilogue(prefix, reason)
    lines += ["    " + line if not line.endswith(":") else line for line in body]
    lines.append("}")
    return "\n".join(lines)


def step_prologue(interface: Interface, places: Places, errors: ErrorTable,
                  relations) -> list[str]:
    """The start of a step, whatever the generator: the clock, the relations, the ``pre``
    values, the input values and the outputs cleared (as :meth:`Reactor.step`)."""
    body = [f"if (clock_ns < m->clock_ns) return {errors.clock};",
            "m->clock_ns = clock_ns;"]
    for relation, code in relations:
        present = [f"in->{_input_field(interface, s)}" for s in relation.signals]
        if relation.kind == "#":
            condition = " + ".join(f"(int){p}" for p in present) + " > 1"
        else:
            condition = f"{present[0]} && !{present[1]}"
        body.append(f"if ({condition}) return {code};")
    for decl, place in places.previous.items():
        value = places.values[decl]
        body += _copy(place.value, value.value, place.ctype)
        body.append(f"{place.has} = {value.has};")
    for signal in interface.inputs:
        input_place = places.values.get(signal.decl)
        if signal.ctype is not None and input_place is not None:
            copy = " ".join(_copy(input_place.value, f"in->{signal.value_field}",
                                  input_place.ctype))
            body.append(f"if (in->{signal.field}) {{ {copy} {input_place.has} = true; }}")
    for signal in interface.outputs:
        body.append(f"out->{signal.field} = false;")
    return body


def step_epilogue(prefix: str, reason) -> list[str]:
    """The end of a step: the mission's status (sticky once failed or aborted) from the
    instant's ``st``."""
    return [
        f"if (st == {prefix.upper()}_FAILED || st == {prefix.upper()}_ABORTED) {{",
        f"    if (m->status != {prefix.upper()}_FAILED && m->status != "
        f"{prefix.upper()}_ABORTED) {{",
        "        m->status = st;",
        f"        m->reason = (st == {prefix.upper()}_FAILED) ? "
        f"{_reason(reason[Status.FAILED])} : {_reason(reason[Status.ABORTED])};",
        "    }",
        f"}} else if (st != {prefix.upper()}_RUNNING && m->status == "
        f"{prefix.upper()}_RUNNING) {{",
        "    m->status = st;",
        "}",
        "return m->status;",
    ]


def _reason(place: Place | None) -> str:
    return "-1" if place is None else f"({place.has} ? {place.value} : -1)"


def _input_field(interface: Interface, decl: ir.SignalDecl) -> str:
    return next(s.field for s in interface.inputs if s.decl is decl)


def _copy(target: str, source: str, ctype: CType) -> list[str]:
    if ctype.kind is Kind.VECTOR:
        return [f"{{ int i; for (i = 0; i < {ctype.size}; ++i) {target}[i] = {source}[i]; }}"]
    return [f"{target} = {source};"]


def _node(number: int, node, graph: Graph, interface: Interface, places: Places) -> str:
    label = f"n{number}:"
    if node.tag == "input":
        field = _input_field(interface, node.signal)
        return f"{label} if (in->{field}) goto n{node.then}; goto n{node.orelse};"
    if node.tag == "data":
        return (f"{label} if ((e = d{node.test}(m, &b)) != 0) return e; "
                f"if (b) goto n{node.then}; goto n{node.orelse};")
    if node.tag == "action":
        return f"{label} if ((e = a{node.action}(m)) != 0) return e; goto n{node.then};"
    leaf = node.leaf
    parts = [label]
    emitted = {id(s) for s in leaf.emitted}
    for signal in interface.outputs:
        if id(signal.decl) in emitted:
            parts.append(f"out->{signal.field} = true;")
            place = places.values.get(signal.decl)
            if signal.ctype is not None and place is not None:
                parts += _copy(f"out->{signal.value_field}", place.value, place.ctype)
    parts += [f"m->state = {leaf.target};", f"st = {STATUS_CODES[leaf.status]};", "goto end;"]
    return " ".join(parts)


# --------------------------------------------------------------------------- reset, tables

def _reset(prefix: str, automaton: AutomatonShape, places: Places, strings: StringTable,
           extra: tuple[str, ...] = ()) -> str:
    body = [f"m->state = {automaton.initial};", *extra, f"m->status = {prefix.upper()}_RUNNING;",
            "m->reason = -1;", "m->clock_ns = 0;"]
    for table in (places.variables, places.values, places.previous):
        for place in table.values():
            body.append(f"{place.has} = false;")
    for decl, place in places.values.items():
        init = decl.init
        if init is None or decl.kind == ir.LOCAL:
            continue
        if isinstance(init, tuple):
            for index, item in enumerate(init):
                body.append(f"{place.value}[{index}] = {c_literal(item, strings)};")
        else:
            body.append(f"{place.value} = {c_literal(init, strings)};")
        body.append(f"{place.has} = true;")
    return _function(f"void {prefix}_reset({prefix}_mem *m)", body)


def _tables(prefix: str, interface: Interface, strings: StringTable, errors: ErrorTable,
            sites: tuple[SiteInfo, ...], phases: list[list[int]], state_count: int,
            phase_function: str | None = None) -> str:
    out = []
    names = ", ".join(c_string(s) for s in strings.names) or "0"
    out.append(f"const char *const {prefix}_string_names[{max(1, len(strings.names))}] = "
               f"{{{names}}};")
    entries = ",\n    ".join(
        f"{{{e.kind.value}, {c_string(e.loc.file)}, {e.loc.line}, {e.loc.col}, "
        f"{c_string(e.message)}}}" for e in errors.entries)
    out.append(f"const orccad_error_info {prefix}_errors[{len(errors.entries)}] = {{\n"
               f"    {entries}\n}};")
    for side, signals, struct in (("inputs", interface.inputs, f"{prefix}_in"),
                                  ("outputs", interface.outputs, f"{prefix}_out")):
        rows = []
        for s in signals:
            value = (f"offsetof({struct}, {s.value_field})" if s.ctype is not None else "0")
            kind = _value_kind(s.ctype)
            size = s.ctype.size if s.ctype is not None and s.ctype.kind is Kind.VECTOR else 0
            rows.append(f"{{{c_string(s.decl.name)}, {kind}, {size}, {ROLE_CODES[s.role]}, "
                        f"{c_string(s.task or '')}, {c_string(s.detail or '')}, "
                        f"offsetof({struct}, {s.field}), {value}}}")
        body = ",\n    ".join(rows) or '{"", 0, 0, 0, "", "", 0, 0}'
        out.append(f"const orccad_signal_info {prefix}_{side}[{max(1, len(signals))}] = {{\n"
                   f"    {body}\n}};")
    site_names = ", ".join(c_string(s.task) for s in sites) or "0"
    out.append(f"const char *const {prefix}_sites[{max(1, len(sites))}] = {{{site_names}}};")
    outputs = {s.decl.name: index for index, s in enumerate(interface.outputs)}
    out += site_tables(prefix, sites, outputs)
    if phase_function is not None:
        out.append(phase_function)
    elif sites:
        phase_rows = ",\n    ".join("{" + ", ".join(map(str, row)) + "}" for row in phases)
        out.append(phase_columns(sites) + "\n"
                   f"static const unsigned char phase_table[{state_count}][{len(sites)}] = "
                   f"{{\n    {phase_rows}\n}};")
        out.append(_function(f"int {prefix}_phase(const {prefix}_mem *m, int site)", [
            f"if (site < 0 || site >= {len(sites)} || m->state < 0 || m->state >= "
            f"{state_count}) return 0;",
            "return phase_table[m->state][site];"]))
    else:
        out.append(_function(f"int {prefix}_phase(const {prefix}_mem *m, int site)",
                             ["(void)m;", "(void)site;", "return 0;"]))
    out.append(_function(f"int {prefix}_string_id(const char *text)", [
        "int i;",
        f"for (i = 0; i < {len(strings.names)}; ++i) {{",
        f"    const char *a = {prefix}_string_names[i];",
        "    const char *b = text;",
        "    while (*a != '\\0' && *a == *b) { ++a; ++b; }",
        "    if (*a == *b) return i;",
        "}",
        "return -1;"]))
    return "\n\n".join(out)


def _value_kind(ctype: CType | None) -> str:
    if ctype is None:
        return "ORCCAD_PURE"
    kind = ctype.element if ctype.kind is Kind.VECTOR else ctype.kind
    base = {Kind.INT: "ORCCAD_INT", Kind.FLOAT: "ORCCAD_FLOAT", Kind.BOOL: "ORCCAD_BOOL",
            Kind.STRING: "ORCCAD_STRING"}[kind]  # type: ignore[index]
    return base + ("_VECTOR" if ctype.kind is Kind.VECTOR else "")
