"""Promela export of the model and of the properties, for an independent check with SPIN.

One Promela process runs the composed automaton, one atomic step per instant: it chooses
every input nondeterministically, walks the state's reaction tree (input tests, tracked data
tests and assignments exactly as the checker's model, free data tests as a nondeterministic
choice), and sets the instant's letter: outputs, ``status`` (0 after the end, 1 running,
2 done, 3 failed, 4 aborted, 5 end of ``on fatal``), ``active`` per Robot-Task, the
fairness flags. The terminal state stutters. SPIN explores this state space itself and
translates the LTL claims itself; only the past operators are encoded here, as monitor
variables updated at each instant (``previously g`` reads the value ``g`` had at the last
instant).

Each property becomes ``ltl NAME { first U (!first && ((fairness && assumptions) ->
property)) }``: ``first`` holds only in SPIN's initial state, which precedes the first
instant, so the property is evaluated from the first instant on; fairness is ``[]<> fpulse``
where a counter over the fairness flags pulses each time it has seen them all
(degeneralization: SPIN's claims stay small). Not exported (the checker handles them): ``next`` (Debian's SPIN is
built without ``X``) and past operators over future ones (SPIN has no past).
"""

from __future__ import annotations

import re
from typing import Iterable

from orccad_app.diagnostics import OrccadError
from orccad_app.lang import ast
from orccad_app.reactive import ir
from orccad_app.reactive.automaton import Action, Automaton, DataBranch, InputTest, Leaf, Node
from orccad_app.reactive.status import Status
from orccad_app.robottask.atoms import Atoms
from orccad_app.robottask.labels import RtLabel
from orccad_app.robottask.signals import SignalRoles
from orccad_app.verify import data
from orccad_app.verify.formula import F, from_ast, is_past

__all__ = ["to_promela", "claim_name"]

_STATUS = {Status.RUNNING: 1, Status.DONE: 2, Status.FAILED: 3, Status.ABORTED: 4}
_OPS = {"+": "+", "-": "-", "*": "*", "<": "<", "<=": "<=", ">": ">", ">=": ">=",
        "==": "==", "!=": "!=", "and": "&&", "or": "||"}


def _ident(prefix: str, name: str) -> str:
    return prefix + re.sub(r"[^A-Za-z0-9]", "_", name)


def claim_name(name: str) -> str:
    """The ``ltl`` claim's name for a property."""
    return _ident("p_", name)


class _Writer:
    def __init__(self, automaton: Automaton, tracked: tuple[ir.VarDecl, ...]):
        self.automaton = automaton
        self.tracked = {v: f"v{i}" for i, v in enumerate(tracked)}
        self.inputs = {s.name: _ident("i_", s.name) for s in automaton.inputs}
        self.outputs = {s.name: _ident("o_", s.name) for s in automaton.outputs
                        if not s.name.startswith("_")}
        labels = automaton.labels or tuple(frozenset() for _ in automaton.trees)
        self.labels = labels
        self.sites = sorted({(l.task, l.site) for ls in labels for l in ls
                             if isinstance(l, RtLabel)}, key=lambda s: s[1])
        self.tasks = sorted({task for task, _ in self.sites})
        self.timers = [n for n, t in enumerate(automaton.data_tests)
                       if data.is_clock_test(t.expr)]
        self.fair = [f"fs{site}" for _, site in self.sites] + [f"ft{n}" for n in self.timers]

    # ------------------------------------------------------------------ expressions
    def expr(self, e: ir.Expr) -> str:
        if isinstance(e, ir.Const):
            return str(int(e.value))
        if isinstance(e, ir.VarRef):
            return self.tracked[e.var]
        if isinstance(e, ir.Unary):
            return f"({'!' if e.op == 'not' else '-'}{self.expr(e.operand)})"
        assert isinstance(e, ir.Binary)
        return f"({self.expr(e.left)} {_OPS[e.op]} {self.expr(e.right)})"

    # ------------------------------------------------------------------ trees
    def tree(self, q: int, node: Node, indent: str) -> list[str]:
        if isinstance(node, Leaf):
            return self.leaf(q, node, indent)
        if isinstance(node, Action):
            line = []
            if node.kind == "assign" and node.target in self.tracked:
                line = [f"{indent}{self.tracked[node.target]} = {self.expr(node.expr)};"]
            return line + self.tree(q, node.next, indent)
        if isinstance(node, InputTest):
            guard = self.inputs[node.signal.name]
            return self._branch(q, f"{guard}", f"!{guard}", node, indent)
        assert isinstance(node, DataBranch)
        test = self.automaton.data_tests[node.number].expr
        if data.is_exact(test, set(self.tracked)):
            return self._branch(q, self.expr(test), "else", node, indent)
        then = self.tree(q, node.then, indent + "   ")
        orelse = ([f"{indent}   ft{node.number} = 0;"] if node.number in self.timers else []) \
            + self.tree(q, node.orelse, indent + "   ")
        return [f"{indent}if", f"{indent}:: true ->", *then, f"{indent}:: true ->", *orelse,
                f"{indent}fi;"]

    def _branch(self, q, then_guard, else_guard, node, indent) -> list[str]:
        return [f"{indent}if", f"{indent}:: {then_guard} ->",
                *self.tree(q, node.then, indent + "   "),
                f"{indent}:: {else_guard} ->", *self.tree(q, node.orelse, indent + "   "),
                f"{indent}fi;"]

    def leaf(self, q: int, leaf: Leaf, indent: str) -> list[str]:
        emitted = {s.name for s in leaf.emitted if not s.name.startswith("_")}
        lines = [f"{indent}{self.outputs[n]} = 1;" for n in sorted(emitted)]
        for task, site in self.sites:
            label = RtLabel(task, site)
            if label in self.labels[q] and label in self.labels[leaf.target] \
                    and f"{task}.start" not in emitted:
                lines.append(f"{indent}fs{site} = 0;")
        if leaf.status == Status.DONE:
            lines.append(f"{indent}if :: bad -> status = 5 :: else -> status = 2 fi;")
        else:
            lines.append(f"{indent}status = {_STATUS[leaf.status]};")
            if leaf.status in (Status.FAILED, Status.ABORTED):
                lines.append(f"{indent}bad = 1;")
        lines.append(f"{indent}state = {leaf.target};")
        return lines

    # ------------------------------------------------------------------ the process
    def declarations(self) -> list[str]:
        lines = ["int state = 0;", "byte status = 0;", "bool bad = 0;", "bool first = 1;"]
        lines += [f"int {name} = 0;" for name in self.tracked.values()]
        lines += [f"bool {name};" for name in self.inputs.values()]
        lines += [f"bool {name};" for name in self.outputs.values()]
        lines += [f"bool {_ident('a_', task)};" for task in self.tasks]
        lines += [f"bool {flag} = 1;" for flag in self.fair]
        lines += ["byte fcount = 0;", "bool fpulse = 1;"]
        return lines

    def fairness_counter(self) -> list[str]:
        """Degeneralization: ``fpulse`` holds when every flag was seen since the last pulse,
        so ``[]<> fpulse`` is the conjunction of ``[]<> flag`` (a small claim for SPIN)."""
        lines = [f"if :: fcount == {k} && {flag} -> fcount = {k + 1} :: else -> skip fi;"
                 for k, flag in enumerate(self.fair)]
        lines.append(f"if :: fcount == {len(self.fair)} -> fpulse = 1; fcount = 0 "
                     ":: else -> fpulse = 0 fi;")
        return lines

    def instant(self, monitors: list[str]) -> list[str]:
        body = ["   :: atomic {"]
        relations = self.automaton.program.relations
        related = {s.name for r in relations for s in r.signals}
        body += [f"      if :: {name} = 1 :: {name} = 0 fi;" for signal, name in
                 self.inputs.items() if signal not in related]
        if related:  # the environment only gives inputs satisfying the relations
            body.append("      " + _related_choice(relations, sorted(related), self.inputs))
        body += [f"      {name} = 0;" for name in self.outputs.values()]
        body += [f"      {flag} = 1;" for flag in self.fair]
        body.append("      if")
        for q, tree in enumerate(self.automaton.trees):
            body.append(f"      :: state == {q} ->")
            if q == self.automaton.terminal:
                body.append("         status = 0;")
            else:
                body += self.tree(q, tree, "         ")
        body.append("      fi;")
        for task in self.tasks:
            states = [q for q, ls in enumerate(self.labels) if any(
                isinstance(l, RtLabel) and l.task == task for l in ls)]
            test = " || ".join(f"state == {q}" for q in states) or "0"
            body.append(f"      {_ident('a_', task)} = ({test});")
        body += [f"      {line}" for line in self.fairness_counter() + monitors]
        body += ["      first = 0", "   }"]
        return body


class _Formulas:
    """Atoms and past monitors of the exported properties."""

    def __init__(self, writer: _Writer, roles: SignalRoles | None):
        self.writer = writer
        self.meaning = Atoms(roles, ()) if roles is not None else None
        self.atoms: dict[tuple, str] = {}
        self.past: dict[F, str] = {}
        self.code: list[str] = []
        self.memory: list[str] = []
        self.updates: list[str] = []

    def atom(self, key: tuple) -> str:
        if key not in self.atoms:
            self.atoms[key] = f"at{len(self.atoms)}"
        return self.atoms[key]

    def atom_expr(self, key: tuple) -> str:
        kind, name = key
        w = self.writer
        if kind == "sig":
            parts = [w.inputs.get(name), w.outputs.get(name)]
            return " || ".join(p for p in parts if p) or "0"
        if kind == "status":
            return f"status == {_STATUS[name]}"
        if kind == "active":
            return _ident("a_", name) if name in w.tasks else "0"
        if self.meaning is None:
            raise ValueError(f"to_promela: the atom {kind}({name}) needs the signal roles")
        signal = self.meaning.signal(key)  # started / ended / raised: by the signal's role
        return w.outputs.get(signal, "0") if signal is not None else "0"

    def text(self, f: F) -> str:
        """The formula in SPIN's syntax; past subformulas become monitor variables."""
        if f in self.past:
            return self.past[f]
        if f.op in ("Y", "S"):
            return self._monitor(f)
        if f.op == "true" or f.op == "false":
            return f.op
        if f.op == "atom":
            return self.atom(f.key)  # type: ignore[arg-type]
        if f.op == "not":
            return f"!({self.text(f.left)})"
        if f.op == "X":
            raise OrccadError("SPIN export: 'next' has no encoding (Debian's SPIN is built "
                              "without the next operator)")
        op = {"and": "&&", "or": "||", "U": "U"}[f.op]
        return f"(({self.text(f.left)}) {op} ({self.text(f.right)}))"

    def _monitor(self, f: F) -> str:
        if not all(is_past(g) for g in (f.left, f.right) if g is not None):
            raise OrccadError("SPIN export: a past operator over a future one "
                              f"({f!r}) has no Promela encoding")
        inner = [self.text(g) for g in (f.left, f.right) if g is not None]
        name = f"pv{len(self.past)}"
        memory = f"pm{len(self.past)}"
        self.past[f] = name
        self.memory.append(memory)
        carried = f"(!first && {memory})"
        value = carried if f.op == "Y" else f"({inner[1]}) || (({inner[0]}) && {carried})"
        self.code.append(f"{name} = ({value});")
        self.updates.append(f"{memory} = " + (inner[0] if f.op == "Y" else name) + ";")
        return name


def to_promela(automaton: Automaton, roles: SignalRoles | None = None, *,
               tracked: tuple[ir.VarDecl, ...] | None = None,
               properties: Iterable[ast.Property] = (),
               assumptions: Iterable[ast.Assumption] = ()) -> str:
    """The Promela model of ``automaton`` with an ``ltl`` claim per property (``roles``, the
    roles of its generated signals, are needed when the properties have atoms
    ``started`` / ``ended`` / ``raised``)."""
    if tracked is None:
        tracked = data.tracked_variables(automaton)
    writer = _Writer(automaton, tracked)
    formulas = _Formulas(writer, roles)
    assumed = [from_ast(a.formula) for a in assumptions]
    claims = []
    for prop in properties:
        body = formulas.text(from_ast(prop.formula))
        premises = ["([]<> fpulse)"] if writer.fair else []
        premises += [f"({formulas.text(a)})" for a in assumed]
        text = f"({' && '.join(premises)}) -> ({body})" if premises else body
        claims.append(f"ltl {claim_name(prop.name)} {{ first U (!first && ({text})) }}")
    monitors = [f"{name} = ({formulas.atom_expr(key)});" for key, name in formulas.atoms.items()]
    monitors += formulas.code + formulas.updates
    lines = [f"/* ORCCAD: mission {automaton.name}, composed automaton of "
             f"{automaton.state_count} states (generated by orccad) */"]
    lines += writer.declarations()
    lines += [f"bool {name};" for name in formulas.atoms.values()]
    lines += [f"bool {name};" for name in formulas.past.values()]
    lines += [f"bool {name} = 0;" for name in formulas.memory]
    lines += ["", "active proctype mission() {", "   do"]
    lines += writer.instant(monitors)
    lines += ["   od", "}", ""]
    lines += claims
    return "\n".join(lines) + "\n"



def _related_choice(relations, names: list[str], inputs: dict) -> str:
    """One nondeterministic choice among the valuations of ``names`` that satisfy every
    relation."""
    from itertools import product
    options = []
    for values in product((1, 0), repeat=len(names)):
        present = {n for n, v in zip(names, values) if v}
        if all(r.holds(present) for r in relations):
            options.append("; ".join(f"{inputs[n]} = {v}" for n, v in zip(names, values)))
    return "if " + " ".join(f":: {o}" for o in options) + " fi;"
