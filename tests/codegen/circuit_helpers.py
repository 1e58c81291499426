"""The circuit generator in the differential tests: a program's circuit C (forced, whatever
``auto`` would choose), built with the strict flags and compared with ``Reactor.step``
record by record (state numbers aside: the circuit has registers, not states)."""

from __future__ import annotations

from pathlib import Path

from orccad_app.codegen.circuit import circuit_of, generate_circuit
from orccad_app.codegen.generate import CProgram
from orccad_app.codegen.mission import generate_chosen
from orccad_app.reactive import ir
from orccad_app.robottask.composition import Composition
from tests.codegen.cbuild import STRICT, build, run_trace
from tests.codegen.differential import first_difference, python_records

__all__ = ["circuit_program", "mission_circuit", "agree_circuit"]


def circuit_program(program: ir.Program, prefix: str, hints=None) -> CProgram:
    """The circuit C of a kernel ``program`` (:class:`NotStatic` when it has none)."""
    circuit = circuit_of(program)
    try:
        return generate_circuit(circuit, prefix, hints=hints)
    finally:
        circuit.manager.release(circuit)


def mission_circuit(composition: Composition, prefix: str) -> CProgram:
    """The circuit C of a composed mission, as ``orccad codegen --generator circuit``."""
    return generate_chosen(composition, prefix, generator="circuit")


def agree_circuit(automaton, program: CProgram, script: Path,
                  flags: tuple[str, ...] = STRICT + ("-O0",)) -> list[dict]:
    """Run ``script`` through the circuit C and ``Reactor.step`` of ``automaton``: the
    records, asserted equal."""
    assert program.generator == "circuit"
    got, _status, stderr = run_trace(build(program, flags), script)
    expected = python_records(automaton, script.read_text(encoding="utf-8"), str(script))
    difference = first_difference(expected, got, states=False)
    assert difference is None, f"{difference}\n{stderr}"
    assert len(got) == len(expected)
    return got
