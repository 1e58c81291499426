"""Textual forms of a compiled automaton: summary, JSON and Graphviz DOT."""

from __future__ import annotations

import json
from typing import Any

from orccad_app.reactive.automaton import Automaton, Transition, transitions
from orccad_app.reactive.expr import format_expr
from orccad_app.reactive.labels import MissionLabel, in_missions, sub_mission_labels
from orccad_app.reactive.status import Status

__all__ = ["to_summary", "to_json", "to_dict", "to_dot", "guard_text", "sub_missions",
           "mission_labels"]


def _signal_type(signal) -> str:
    return signal.name if signal.type is None else f"{signal.name} : {signal.type}"


def guard_text(automaton: Automaton, t: Transition) -> str:
    """``A and not B and [x > 2]``, or ``true`` for an unconditional transition."""
    parts = [name if value else f"not {name}" for name, value in
             ((s.name, v) for s, v in t.inputs)]
    for number, value in t.data:
        text = format_expr(automaton.data_tests[number].expr)
        parts.append(f"[{text}]" if value else f"[not ({text})]")
    return " and ".join(parts) or "true"


def _action_text(action) -> str:
    if action.kind == "assign":
        return f"{action.target.name} := {format_expr(action.expr)}"
    if action.target.name in ("_failed", "_aborted"):  # the mission's status and its reason
        expr = action.expr
        if getattr(expr, "op", None) == "last":  # a later emission in the instant wins
            expr = expr.right
        return f"{action.target.name[1:]} {getattr(expr, 'value', None) or format_expr(expr)}"
    return f"emit {action.target.name}({format_expr(action.expr)})"


def to_dict(automaton: Automaton) -> dict[str, Any]:
    """A JSON-ready description: interface, then every state and its transitions."""
    states = []
    by_source: dict[int, list] = {i: [] for i in range(automaton.state_count)}
    for t in automaton.transitions():
        by_source[t.source].append({
            "inputs": {s.name: v for s, v in t.inputs},
            "data": [[format_expr(automaton.data_tests[n].expr), v] for n, v in t.data],
            "actions": [_action_text(a) for a in t.actions],
            "outputs": [s.name for s in t.emitted],
            "status": t.status,
            "target": t.target,
        })
    for state in range(automaton.state_count):
        states.append({
            "id": state,
            "waiting_at": [str(loc) for loc in automaton.waiting[state]],
            "sub_missions": [m.to_dict() for m in in_missions(
                automaton.labels[state] if automaton.labels else (), automaton.waiting[state])],
            "transitions": by_source[state],
        })
    return {
        "name": automaton.name,
        "inputs": [{"name": s.name, "type": s.type} for s in automaton.inputs],
        "outputs": [{"name": s.name, "type": s.type} for s in automaton.outputs],
        "variables": [v.name for v in automaton.variables],
        "initial": automaton.initial,
        "state_count": automaton.state_count,
        "transition_count": sum(len(s["transitions"]) for s in states),
        "states": states,
    }


def to_json(automaton: Automaton) -> str:
    return json.dumps(to_dict(automaton), indent=2)


def to_summary(automaton: Automaton) -> str:
    """A human overview: sizes, interface, and the transitions of each state."""
    lines = [
        f"automaton {automaton.name}",
        f"  states: {automaton.state_count}",
        f"  transitions: {automaton.transition_count}",
        f"  inputs: {', '.join(_signal_type(s) for s in automaton.inputs) or '-'}",
        f"  outputs: {', '.join(_signal_type(s) for s in automaton.outputs) or '-'}",
    ]
    visible = [v.name for v in automaton.variables if not v.hidden]
    hidden = sum(1 for v in automaton.variables if v.hidden)
    if visible or hidden:
        lines.append(f"  variables: {', '.join(visible) or '-'}"
                     + (f" (+{hidden} counters/timers)" if hidden else ""))
    current = None
    for t in automaton.transitions():
        if t.source != current:
            current = t.source
            where = ", ".join(str(loc) for loc in automaton.waiting[t.source])
            label = "initial" if t.source == automaton.initial else f"waiting at {where}" \
                if where else "terminated"
            lines.append(f"state {t.source} ({label}{_missions_in(automaton, t.source)})")
        effects = [_action_text(a) for a in t.actions] + [s.name for s in t.emitted]
        tail = f" / {', '.join(effects)}" if effects else ""
        # the terminated state's own loop keeps the status its entry set (done, failed or
        # aborted): labelling it would say "[done]" after a failure
        ended = t.status != Status.RUNNING and t.source != automaton.terminal
        status = f" [{t.status}]" if ended else ""
        lines.append(f"  {guard_text(automaton, t)}{tail} -> {t.target}{status}")
    return "\n".join(lines)


def sub_missions(automaton: Automaton, state: int) -> list[MissionLabel]:
    """The sub-mission instances (``run mission M``) state ``state`` is in, outermost first."""
    return sub_mission_labels(automaton.labels[state] if automaton.labels else ())


def mission_labels(automaton: Automaton, state: int) -> list[str]:
    """The sub-missions state ``state`` is in, as ``M#n (file:line) inside file:line``."""
    return [label.text() for label in sub_missions(automaton, state)]


def _missions_in(automaton: Automaton, state: int) -> str:
    inside = mission_labels(automaton, state)
    return f"; in mission {', '.join(inside)}" if inside else ""


def _quote(text: str) -> str:
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'


def to_dot(automaton: Automaton) -> str:
    """Graphviz DOT: one node per state, one edge per transition labelled guard / effects."""
    lines = [f"digraph {_quote(automaton.name)} {{", "  rankdir=LR;",
             '  node [shape=circle, fontname="Helvetica"];',
             '  edge [fontname="Helvetica", fontsize=10];',
             '  start [shape=point];', f"  start -> s{automaton.initial};"]
    for state in range(automaton.state_count):
        final = any(t.status != Status.RUNNING
                    for t in transitions(state, automaton.trees[state]))
        shape = "doublecircle" if final else "circle"
        lines.append(f"  s{state} [label={_quote(str(state))}, shape={shape}];")
    for t in automaton.transitions():
        effects = [_action_text(a) for a in t.actions] + [s.name for s in t.emitted]
        label = guard_text(automaton, t) + (" / " + ", ".join(effects) if effects else "")
        lines.append(f"  s{t.source} -> s{t.target} [label={_quote(label)}];")
    lines.append("}")
    return "\n".join(lines)

