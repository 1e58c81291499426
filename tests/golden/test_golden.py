"""Behaviour unchanged: every shipped mission's compiled automaton, run report and trace.

The references in ``tests/golden/data/`` were produced by ``python -m tests.golden.regenerate``.
When a change of behaviour is intended, regenerate them and explain each changed reference in
the commit message; otherwise a difference here is a regression.
"""

from __future__ import annotations

import difflib

import pytest

from tests.golden.cases import CASES, Case
from tests.golden.regenerate import produce, reference


def _first_difference(expected: bytes, actual: bytes) -> str:
    diff = difflib.unified_diff(expected.decode().splitlines(), actual.decode().splitlines(),
                                "reference", "now", n=1, lineterm="")
    return "\n".join(list(diff)[:40])


@pytest.mark.parametrize("case", CASES, ids=[case.name for case in CASES])
def test_output_is_byte_identical_to_the_reference(case: Case) -> None:
    expected = reference(case)
    actual = produce(case)
    assert actual.status == expected.status
    assert actual.stdout == expected.stdout, _first_difference(expected.stdout, actual.stdout)
    if case.trace:
        assert actual.trace == expected.trace, _first_difference(expected.trace or b"",
                                                                 actual.trace or b"")
