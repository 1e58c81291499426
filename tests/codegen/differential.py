"""The Python side of the differential tests: what ``Reactor.step`` does on a script, in the
records the generated ``PREFIX_main --trace`` prints (those of ``orccad react --jsonl``, plus
the state reached and the instant's own status, or the located error)."""

from __future__ import annotations

import copy

from orccad_app.diagnostics import OrccadError
from orccad_app.reactive.expr import Store
from orccad_app.reactive.runtime import Reactor
from orccad_app.reactive.script import parse_script

__all__ = ["python_records", "first_difference"]


_PRISTINE: dict[int, tuple] = {}


def _fresh(automaton) -> Reactor:
    """A new reactor of ``automaton`` without lowering its trees again (a copy of a pristine
    one, with a store of its own holding the initial values)."""
    found = _PRISTINE.get(id(automaton))
    if found is None or found[0] is not automaton:
        found = _PRISTINE[id(automaton)] = (automaton, Reactor(automaton))
    reactor = copy.copy(found[1])
    reactor.store = Store()
    reactor.store.values = dict(found[1].store.values)
    return reactor


def python_records(automaton, text: str, name: str) -> list[dict]:
    """Run ``text`` (a script) on a fresh reactor of ``automaton``."""
    instants = parse_script(text, name, automaton.inputs)
    timed = any(i.time_ns is not None for i in instants)
    reactor = _fresh(automaton)
    records: list[dict] = []
    for number, instant in enumerate(instants, start=1):
        try:
            step = reactor.step(instant.inputs, instant.time_ns)
        except OrccadError as error:
            loc = error.location
            records.append({"instant": number, "error": {
                "file": loc.file if loc else "<unknown>", "line": loc.line if loc else 0,
                "col": loc.col if loc else 0, "message": error.message}})
            break
        record = {"instant": number, "inputs": list(instant.inputs),
                  "outputs": list(step.outputs), "values": reactor.values(step),
                  "status": reactor.status}
        if reactor.reason is not None:
            record["reason"] = reactor.reason
        if timed:
            record["time_s"] = reactor.store.clock_ns / 1e9
        record["state"] = step.target
        record["step_status"] = step.status
        records.append(record)
    return records


def _plain(record: dict) -> dict:
    """A record as JSON reads it back (tuples as lists); the C error's code dropped."""
    out = {}
    for key, value in record.items():
        if key == "values":
            value = {k: list(v) if isinstance(v, tuple) else v for k, v in value.items()}
        if key == "error":
            value = {k: v for k, v in value.items() if k != "code"}
        out[key] = value
    return out


def first_difference(expected: list[dict], got: list[dict], *,
                     states: bool = True) -> str | None:
    """A description of the first record that differs, or ``None``; ``states=False``: the
    state numbers are not compared (the circuit's C has none, :mod:`orccad_app.codegen.
    circuit`)."""
    for index, (a, b) in enumerate(zip(expected, got)):
        a, b = _plain(a), _plain(b)
        if not states:
            a.pop("state", None)
            b.pop("state", None)
        if a != b or any(type(a["values"][k]) is not type(b["values"][k])
                         for k in a.get("values", {}) if k in b.get("values", {})):
            return f"instant {index + 1}: Python {a}\n          C      {b}"
    if len(expected) != len(got):
        return f"Python printed {len(expected)} records, C {len(got)}"
    return None
