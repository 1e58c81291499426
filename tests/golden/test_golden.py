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


NOT_RUN = {"ABRO": "runs no Robot-Task: orccad run refuses it (exit 2), orccad react runs it"}
"""Shipped missions without a run reference, and why."""


def _missions(path) -> list[str]:
    """The missions a shipped file declares (``mission Name {`` at the start of a line)."""
    import re

    return re.findall(r"^mission\s+(\w+)", path.read_text(encoding="utf-8"), re.M)


def test_every_shipped_mission_has_a_compile_and_a_run_reference() -> None:
    """A mission added to missions/ without golden references would escape the
    byte-identity check: each of its missions needs a compile case and a run case."""
    from tests.golden.cases import MISSIONS

    def covers(command: str, path: str, mission: str, only: bool) -> bool:
        for case in CASES:
            argv = list(case.argv)
            if argv[:2] != [command, path]:
                continue
            if ("-m" in argv and argv[argv.index("-m") + 1] == mission) or \
                    ("-m" not in argv and only):
                return True
        return False

    missing = []
    for path in sorted(MISSIONS.glob("*.orc")):
        names = _missions(path)
        relative = f"missions/{path.name}"
        for name in names:
            for command in ("compile", "run"):
                if command == "run" and name in NOT_RUN:
                    continue
                if not covers(command, relative, name, len(names) == 1):
                    missing.append(f"{command} {relative} -m {name}")
    assert not missing, "no golden case for: " + "; ".join(missing)
    names = [case.name for case in CASES]
    assert len(set(names)) == len(names), "two golden cases share a reference file"
