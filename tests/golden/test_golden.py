"""Behaviour unchanged: every shipped mission's compiled automaton, run report and trace.

The references in ``tests/golden/data/`` were produced by ``python -m tests.golden.regenerate``.
When a change of behaviour is intended, regenerate them and explain each changed reference in
the commit message; otherwise a difference here is a regression.

Numbers are compared with the tolerance stated in ``tests/golden/compare.py`` (floating-point
kernels differ between processors in the last digits); structure, names, statuses, integers and
the order of events exactly. Byte-identity is a determinism test on this machine: the same
command run twice gives the same bytes.
"""

from __future__ import annotations

import pytest

from tests.golden.cases import CASES, Case
from tests.golden.compare import compare_json, compare_trace
from tests.golden.regenerate import Output, produce, reference

_PRODUCED: dict[str, Output] = {}
"""Each case's output, kept for the determinism test (which runs a few cases a second time)."""


def _produce_once(case: Case) -> Output:
    if case.name not in _PRODUCED:
        _PRODUCED[case.name] = produce(case)
    return _PRODUCED[case.name]


@pytest.mark.parametrize("case", CASES, ids=[case.name for case in CASES])
def test_output_matches_the_reference(case: Case) -> None:
    expected = reference(case)
    actual = _produce_once(case)
    assert actual.status == expected.status, actual.stdout[-2000:]
    mismatch = compare_json(expected.stdout, actual.stdout)
    assert mismatch is None, f"{case.name} output: {mismatch}"
    if case.trace:
        assert actual.trace is not None
        mismatch = compare_trace(expected.trace or b"", actual.trace)
        assert mismatch is None, f"{case.name} trace: {mismatch}"


DETERMINISM_CASES = ("compile-auv_survey", "run-auv_survey-trace", "run-arm_recovery-trace",
                     "run-auv_waypoints-trace")
"""Cases run a second time: float-heavy reports and traces across Robot-Task boundaries."""


@pytest.mark.parametrize("name", DETERMINISM_CASES)
def test_the_same_command_twice_gives_the_same_bytes(name: str) -> None:
    case = next(case for case in CASES if case.name == name)
    first = _produce_once(case)
    second = produce(case)
    assert second.status == first.status
    assert second.stdout == first.stdout
    assert second.trace == first.trace


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


def test_the_golden_data_stays_under_a_megabyte() -> None:
    """The references are read by people and cloned by everyone: a run report groups a
    sustained output, a compile reference keeps its states as a digest, traces are xz."""
    from tests.golden.cases import DATA

    total = sum(path.stat().st_size for path in DATA.iterdir() if path.is_file())
    assert total < 1_000_000, f"tests/golden/data holds {total} bytes"
