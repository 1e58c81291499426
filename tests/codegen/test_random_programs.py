"""Random kernel programs (``tests/reactive/strategies.py``: locals, traps, suspension,
``pre``, ``combine``, counted aborts, sub-mission regions, relations) compiled as ``orccad
codegen`` compiles them (a second emission the inputs make is a run-time error), generated as C
and run on random input sequences: the C agrees with ``Reactor.step`` state by state. Each
example compiles one program (``-O0``, cached by content), so the examples are few."""

from __future__ import annotations

import itertools

from hypothesis import HealthCheck, assume, given, settings

from orccad_app.codegen.generate import generate
from orccad_app.codegen.static_types import CodegenError
from orccad_app.diagnostics import OrccadError
from orccad_app.reactive.compiler import compile_program
from tests.codegen.cbuild import STRICT, build, run_trace
from tests.codegen.differential import first_difference, python_records
from tests.reactive.strategies import expand, input_sequences, programs

_NAMES = itertools.count()


def _script(sequence, relations) -> str:
    lines = []
    for inputs, clock_ns in sequence:
        if relations and "A" in inputs:
            inputs = {k: v for k, v in inputs.items() if k != "B"}
        parts = [f"@{clock_ns / 1e9!r}"]
        parts += [name if value is None else f"{name}({value})" for name, value in inputs.items()]
        lines.append(" ".join(parts))
    return "\n".join(lines) + "\n"


@settings(max_examples=15, deadline=None, derandomize=True, database=None,
          suppress_health_check=[HealthCheck.filter_too_much, HealthCheck.too_slow,
                                 HealthCheck.data_too_large,
                                 HealthCheck.function_scoped_fixture])
@given(program=programs(), sequence=input_sequences())
def test_random_programs_agree_in_c(program, sequence, tmp_path_factory):
    try:
        automaton = compile_program(expand(program), max_states=300,
                                    defer_double_emissions=True)
    except OrccadError:
        assume(False)  # non-causal or too big: tests/reactive covers the refusal
    try:
        generated = generate(automaton, "random")
    except CodegenError:
        assume(False)  # a type C cannot hold (tests/codegen/test_interface.py)
    binary = build(generated, STRICT + ("-O0",))
    path = tmp_path_factory.mktemp("r", numbered=True) / f"r{next(_NAMES)}.in"
    path.write_text(_script(sequence, program.relations))
    expected = python_records(automaton, path.read_text(), str(path))
    got, _status, stderr = run_trace(binary, path)
    assert first_difference(expected, got) is None, first_difference(expected, got)
