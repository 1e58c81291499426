"""SCXML export of a compiled automaton (W3C State Chart XML, Python datamodel).

The automaton reacts to one event per instant, ``react``, whose data carries the presence of
every input (a boolean per input, under the name :func:`identifier` gives it), the value of
each valued input (``<id>_value``: its value in this instant, or its last one) and the clock
in nanoseconds (``clock``). Each
state's reaction tree becomes a small tree of *transient* states joined by eventless
transitions: input tests and data tests are ``cond`` s, assignments and valued emissions are
``<assign>`` s in execution order, and the leaf assigns ``emitted`` (the outputs, space
separated, declaration order) and ``status`` before reaching the next stable state. A
consumer sends ``react`` with the inputs of the instant and reads ``emitted``/``status``.
"""

from __future__ import annotations

import re
from xml.sax.saxutils import quoteattr

from orccad_app.reactive import ir
from orccad_app.reactive.automaton import Action, Automaton, InputTest, Leaf
from orccad_app.reactive.status import Status

__all__ = ["to_scxml", "identifier"]


def identifier(name: str) -> str:
    """A Python identifier for a signal or variable name (``TrackPID.start`` → ``TrackPID_start``)."""
    return re.sub(r"\W", "_", name)


class _Writer:
    def __init__(self, automaton: Automaton):
        self.automaton = automaton
        self.lines: list[str] = []
        self.vars = {v: f"var_{identifier(v.name)}_{i}" for i, v in enumerate(automaton.variables)}
        self.counter = 0

    def expr(self, e: ir.Expr) -> str:
        kind = type(e)
        if kind is ir.Const:
            return repr(e.value)
        if kind is ir.VarRef:
            return self.vars[e.var]
        if kind is ir.SigValue:
            return f"value_{identifier(e.signal.name)}"
        if kind is ir.PreValue:
            return f"pre_value_{identifier(e.signal.name)}"
        if kind is ir.Fault:
            return f"error({e.message!r})"
        if kind is ir.Clock:
            return "clock"
        if kind is ir.VectorExpr:
            return "[" + ", ".join(self.expr(i) for i in e.items) + "]"
        if kind is ir.Unary:
            return f"({'not ' if e.op == 'not' else '-'}{self.expr(e.operand)})"
        if e.op in ("min", "max"):
            return f"{e.op}({self.expr(e.left)}, {self.expr(e.right)})"
        if e.op == "last":
            return self.expr(e.right)
        return f"({self.expr(e.left)} {e.op} {self.expr(e.right)})"

    def node(self, state: int, tree) -> str:
        """Write the transient state of ``tree``; return its id."""
        self.counter += 1
        sid = f"s{state}_n{self.counter}"
        out = self.lines
        out.append(f'  <state id="{sid}">')
        if isinstance(tree, Leaf):
            emitted = " ".join(s.name for s in tree.emitted)
            out.append(f'    <transition target="s{tree.target}">')
            out.append(f'      <assign location="emitted" expr={quoteattr(repr(emitted))}/>')
            out.append(f'      <assign location="status" expr={quoteattr(repr(tree.status.value))}/>')
            out.append("    </transition>")
            out.append("  </state>")
            return sid
        if isinstance(tree, Action):
            out.append("  </state>")
            index = len(out) - 1
            target = self.node(state, tree.next)
            location = self.vars[tree.target] if tree.kind == "assign" else \
                f"value_{identifier(tree.target.name)}"
            out[index:index] = [f'    <transition target="{target}">',
                                f'      <assign location="{location}" '
                                f'expr={quoteattr(self.expr(tree.expr))}/>',
                                "    </transition>"]
            return sid
        cond = f"in_{identifier(tree.signal.name)}" if isinstance(tree, InputTest) \
            else self.expr(self.automaton.data_tests[tree.number].expr)
        out.append("  </state>")
        index = len(out) - 1
        then, orelse = self.node(state, tree.then), self.node(state, tree.orelse)
        out[index:index] = [f'    <transition cond={quoteattr(cond)} target="{then}"/>',
                            f'    <transition target="{orelse}"/>']
        return sid


def to_scxml(automaton: Automaton) -> str:
    """The automaton as an SCXML document (see the module docstring for its protocol)."""
    writer = _Writer(automaton)
    body = writer.lines
    # the event's data is copied into the datamodel: the transient states' eventless
    # transitions read it from there
    copies = [f'      <assign location="in_{identifier(s.name)}" expr="_event.data.{identifier(s.name)}"/>'
              for s in automaton.inputs]
    copies += [f'      <assign location="value_{identifier(s.name)}" '
               f'expr="_event.data.{identifier(s.name)}_value"/>'
               for s in automaton.inputs if s.valued]
    copies.append('      <assign location="clock" expr="_event.data.clock"/>')
    for state, tree in enumerate(automaton.trees):
        index = len(body)
        root = writer.node(state, tree)
        react = [f'    <transition event="react" target="{root}">', *copies, "    </transition>"] \
            if copies else [f'    <transition event="react" target="{root}"/>']
        body[index:index] = [f'  <state id="s{state}">', *react, "  </state>"]
    data = [("emitted", "''"), ("status", repr(Status.RUNNING.value)), ("clock", "0")]
    data += [(f"in_{identifier(s.name)}", "False") for s in automaton.inputs]
    data += [(name, "None") for name in writer.vars.values()]
    data += [(f"value_{identifier(s.name)}", "None")
             for s in (*automaton.inputs, *automaton.outputs) if s.valued]
    head = [f'<scxml xmlns="http://www.w3.org/2005/07/scxml" version="1.0" '
            f'initial="s{automaton.initial}" datamodel="python" '
            f'name={quoteattr(identifier(automaton.name))}>', "  <datamodel>"]
    head += [f'    <data id="{name}" expr="{expr}"/>' for name, expr in data]
    head.append("  </datamodel>")
    return "\n".join(['<?xml version="1.0" encoding="UTF-8"?>', *head, *body, "</scxml>"])
