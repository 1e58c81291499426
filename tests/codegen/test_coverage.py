"""Coverage-directed differential tests: every transition the search reaches from the Python
reactor (:mod:`tests.codegen.coverage`) is taken by the generated C the same way — status,
state reached, outputs and their values, run-time errors — on every shipped mission; the
coverage is printed at the end of the session."""

from __future__ import annotations

import pytest

from tests.codegen.cbuild import build, run_traces
from tests.codegen.conftest import COVERAGE, SHIPPED, generated
from tests.codegen.coverage import search
from tests.codegen.differential import first_difference, python_records

#: the reactions the search may try per mission (about a second of Python on an idle machine)
BUDGET = 12_000


@pytest.mark.parametrize("stem,mission", SHIPPED)
def test_every_reached_transition_agrees(stem, mission, tmp_path):
    made = generated(stem, mission)
    automaton = made.composition.automaton
    sizes = {d.name: t.size for d, t in made.program.types.places.items()
             if getattr(d, "kind", None) == "input" and t.size}
    coverage = search(automaton, max_steps=BUDGET, sizes=sizes)
    scripts = [*coverage.scripts.values(), *coverage.errors]
    # a script that is a prefix of another is checked by the longer one
    texts = sorted({"\n".join(lines) + "\n" for lines in scripts})
    maximal = [t for i, t in enumerate(texts)
               if not (i + 1 < len(texts) and texts[i + 1].startswith(t))]
    paths = []
    for number, text in enumerate(maximal):
        path = tmp_path / f"s{number}.in"
        path.write_text(text)
        paths.append(path)
    got = run_traces(build(made.program), paths)
    for path in paths:
        expected = python_records(automaton, path.read_text(), str(path))
        difference = first_difference(expected, got[str(path)])
        assert difference is None, f"{path.read_text()}\n{difference}"
    COVERAGE.append(f"{mission}: {coverage.reached} of {coverage.total} transitions reached "
                    f"and agreeing ({100 * coverage.reached / coverage.total:.0f} %), "
                    f"{len(maximal)} scripts, {coverage.steps} reactions searched")
    assert coverage.reached >= 0.6 * coverage.total
