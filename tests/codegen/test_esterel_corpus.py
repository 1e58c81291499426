"""The Esterel v5 / HipHop corpus (``tests/reactive/esterel/``) through the generated C: each
program's published trace, run by its ``PREFIX_main``, gives the published outputs and the
records of the Python reactor (state by state)."""

from __future__ import annotations

import pytest

from orccad_app.codegen.generate import generate
from orccad_app.lang.parser import parse
from orccad_app.reactive.compiler import compile_program
from orccad_app.reactive.lower import lower_mission
from tests.codegen.cbuild import STRICT, build, run_trace
from tests.codegen.differential import first_difference, python_records
from tests.reactive.test_esterel_suite import CASES, FOLDER, _text, _trace


@pytest.mark.parametrize("name", CASES)
def test_published_trace_through_c(name, tmp_path):
    program = parse((FOLDER / f"{name}.orc").read_text(), f"{name}.orc")
    automaton = compile_program(lower_mission(program, program.missions[-1]))
    binary = build(generate(automaton, "p_" + name.replace("-", "_")), STRICT + ("-O0",))
    steps = _trace(name)
    script = tmp_path / f"{name}.in"
    script.write_text("".join(" ".join(sorted(inputs)) + "\n" for inputs, _ in steps))
    got, status, stderr = run_trace(binary, script)
    expected = python_records(automaton, script.read_text(), str(script))
    assert first_difference(expected, got) is None, first_difference(expected, got)
    assert len(got) == len(steps), stderr
    for number, (record, (inputs, outputs)) in enumerate(zip(got, steps), start=1):
        shown = {f"{o}({_text(record['values'][o])})" if o in record["values"] else o
                 for o in record["outputs"]}
        assert shown == outputs, f"instant {number} (inputs {sorted(inputs)})"
