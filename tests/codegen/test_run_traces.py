"""The inputs recorded in ``orccad run`` traces of the shipped missions (the golden traces of
``tests/golden/data/``: every reaction with an input or an output, at its time) replayed
through the generated C and through ``Reactor.step``: the same records, state by state."""

from __future__ import annotations

import csv
import io
import json
import re

import pytest

from orccad_app.pipeline import load
from tests.codegen.cbuild import build, run_trace
from tests.codegen.conftest import generated
from tests.codegen.differential import first_difference, python_records
from tests.golden.cases import CASES, ROOT
from tests.golden.regenerate import trace_bytes

TRACED = [case for case in CASES if case.trace]


def _mission(argv: tuple[str, ...]) -> tuple[str, str]:
    path = ROOT / argv[1]
    if "-m" in argv:
        return path.stem, argv[argv.index("-m") + 1]
    return path.stem, load(path).program.missions[0].name


def _injected(argv: tuple[str, ...]) -> dict[str, str]:
    """The values given to valued inputs on the command line (the trace records names)."""
    values = {}
    for index, arg in enumerate(argv[:-1]):
        if arg == "--inject":
            match = re.fullmatch(r"([\w.]+)\((.*)\)@.*", argv[index + 1])
            if match:
                values[match.group(1)] = match.group(2)
    return values


def script_of(case) -> str:
    """The reactions of the case's trace as an input script."""
    values = _injected(case.argv)
    rows = list(csv.DictReader(io.StringIO(trace_bytes(case.name).decode())))
    lines = []
    for row in rows:
        if row["event"] != "reaction":
            continue
        inputs = json.loads(row["value"])["inputs"]
        parts = [f"@{int(row['time_ns']) / 1e9!r}"]
        parts += [f"{name}({values[name]})" if name in values else name for name in inputs]
        lines.append(" ".join(parts))
    return "\n".join(lines) + "\n"


def test_the_recorded_traces_hold_reactions():
    assert sum(script_of(case).count("\n") for case in TRACED) >= 200


@pytest.mark.parametrize("case", TRACED, ids=[c.name for c in TRACED])
def test_recorded_run_inputs_agree(case, tmp_path):
    stem, mission = _mission(case.argv)
    made = generated(stem, mission)
    path = tmp_path / f"{case.name}.in"
    path.write_text(script_of(case))
    expected = python_records(made.composition.automaton, path.read_text(), str(path))
    got, status, stderr = run_trace(build(made.program), path)
    assert first_difference(expected, got) is None, first_difference(expected, got)
    assert status in (0, 1), stderr
