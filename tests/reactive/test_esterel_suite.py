"""Esterel v5 / HipHop test programs with their published traces, as a regression suite.

Each ``tests/reactive/esterel/NAME.orc`` translates ``test/NAME.strl`` of HipHop's test
suite (https://github.com/manuel-serrano/hiphop, commit ff9a3850, the Esterel v5 sources HipHop
is checked against), and ``NAME.trace`` transcribes the published trace ``test/NAME.in`` /
``test/NAME.out``: one instant per line, ``inputs -> outputs`` (``-`` for none). The last
mission of the file is run on the inputs; the outputs of every instant (names and values) must
be the published ones (compared as sets: HipHop prints them in emission order). Each file
names its source in its header.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from orccad_app.lang.parser import parse
from orccad_app.reactive.compiler import compile_program
from orccad_app.reactive.lower import lower_mission
from orccad_app.reactive.runtime import Reactor

FOLDER = Path(__file__).parent / "esterel"
CASES = sorted(p.stem for p in FOLDER.glob("*.orc"))


def _text(value) -> str:
    if isinstance(value, bool):
        return str(value).lower()
    return str(value)


def _trace(name: str) -> list[tuple[set[str], set[str]]]:
    steps = []
    for line in (FOLDER / f"{name}.trace").read_text().splitlines():
        if line.startswith("#") or not line.strip():
            continue
        inputs, outputs = (side.split() for side in line.split("->"))
        steps.append(({i for i in inputs if i != "-"}, {o for o in outputs if o != "-"}))
    return steps


def test_the_suite_has_at_least_30_programs():
    assert len(CASES) >= 30
    for name in CASES:
        header = (FOLDER / f"{name}.orc").read_text().splitlines()[0]
        assert "github.com/manuel-serrano/hiphop" in header


@pytest.mark.parametrize("name", CASES)
def test_published_trace(name):
    program = parse((FOLDER / f"{name}.orc").read_text(), f"{name}.orc")
    automaton = compile_program(lower_mission(program, program.missions[-1]))
    reactor = Reactor(automaton)
    for number, (inputs, expected) in enumerate(_trace(name), start=1):
        reaction = reactor.react(inputs)
        got = {f"{o}({_text(reaction.values[o])})" if o in reaction.values else o
               for o in reaction.outputs}
        assert got == expected, f"instant {number} (inputs {sorted(inputs)})"
