"""The golden comparison: last-digit float differences pass, anything else fails."""

from __future__ import annotations

import json

from tests.golden.regenerate import trace_bytes
from tests.golden.compare import REL_TOL, compare_json, compare_trace


def _doc(**fields: object) -> bytes:
    base: dict[str, object] = {"mission": "AuvSurvey", "status": "done", "robustness":
                               14.926866542322346, "ticks": 6000, "tasks": ["Dive", "Survey"]}
    base.update(fields)
    return json.dumps(base, indent=2).encode()


def test_a_difference_in_the_17th_significant_digit_passes() -> None:
    # the AMD EPYC failure of issue 28: ...346 against ...347
    assert compare_json(_doc(), _doc(robustness=14.926866542322347)) is None


def test_a_difference_beyond_the_tolerance_fails() -> None:
    found = compare_json(_doc(), _doc(robustness=14.926866542322346 * (1 + 100 * REL_TOL)))
    assert found is not None and found.where == "$.robustness"


def test_structure_names_statuses_and_integers_are_exact() -> None:
    assert compare_json(_doc(), _doc(status="aborted")) is not None
    assert compare_json(_doc(), _doc(mission="AuvSurveyX")) is not None
    assert compare_json(_doc(), _doc(ticks=6001)) is not None
    assert compare_json(_doc(), _doc(ticks=6000.0)) is not None
    assert compare_json(_doc(), _doc(tasks=["Survey", "Dive"])) is not None
    assert compare_json(_doc(), _doc(tasks=["Dive"])) is not None
    assert compare_json(_doc(), _doc(extra=None)) is not None
    assert compare_json(_doc(), b'{"robustness": NaN}') is not None


def _trace() -> bytes:
    return trace_bytes("run-auv_survey-trace")


def test_a_trace_with_last_digit_differences_passes_and_reordered_events_fail() -> None:
    trace = _trace()
    assert compare_trace(trace, trace) is None
    lines = trace.decode().splitlines(keepends=True)
    value_row = next(i for i, line in enumerate(lines) if line.count(".") > 3 and i > 1)
    nudged = lines[:]
    nudged[value_row] = _nudge_last_digit(lines[value_row])
    assert nudged[value_row] != lines[value_row]
    assert compare_trace(trace, "".join(nudged).encode()) is None
    swapped = lines[:]
    swapped[1], swapped[2] = swapped[2], swapped[1]
    assert compare_trace(trace, "".join(swapped).encode()) is not None
    assert compare_trace(trace, "".join(lines[:-1]).encode()) is not None


def _nudge_last_digit(line: str) -> str:
    """``line`` with the last digit of its first long decimal number changed by one."""
    import re

    match = re.search(r"\d\.\d{12,}", line)
    assert match is not None, line
    end = match.end() - 1
    digit = "1" if line[end] != "1" else "2"
    return line[:end] + digit + line[end + 1:]
