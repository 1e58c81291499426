"""Compare a golden command's output with its reference: numbers within a stated tolerance,
everything else exactly.

Byte-identical floating-point output across processors is not something numpy's and MuJoCo's
SIMD-dispatched kernels promise (an AMD EPYC without AVX-512 differs from the reference machine
in the 17th significant digit of STL robustness values). The golden comparison therefore
accepts a number that agrees with its reference within ``REL_TOL`` (relative) or ``ABS_TOL``
(absolute, for values that are zero up to rounding); structure, keys, names, statuses, integers
and the order of the trace's events must match exactly. Byte-identity is kept as a separate
determinism test on one machine (the same command twice gives the same bytes).
"""

from __future__ import annotations

import csv
import io
import json
import math
from dataclasses import dataclass

REL_TOL = 1e-9
"""Relative tolerance of a floating-point number against its reference."""

ABS_TOL = 1e-12
"""Absolute tolerance, for numbers whose reference is zero up to rounding."""

TRACE_EXACT_COLUMNS = ("time_ns", "event", "module", "port", "job")
"""Trace columns compared exactly: when, what, where, which job (event order included)."""


@dataclass(frozen=True)
class Mismatch:
    """Where an output first departs from its reference.

    :param where: a JSON path (``$.robot_tasks[2].end_s``) or ``row N, column`` of the trace.
    :param expected: the reference's value there.
    :param actual: the produced value there.
    """

    where: str
    expected: object
    actual: object

    def __str__(self) -> str:
        return f"{self.where}: reference {self.expected!r}, now {self.actual!r}"


def _numbers_agree(expected: float, actual: float) -> bool:
    if math.isnan(expected) or math.isnan(actual):
        return math.isnan(expected) and math.isnan(actual)
    if math.isinf(expected) or math.isinf(actual):
        return expected == actual
    return math.isclose(expected, actual, rel_tol=REL_TOL, abs_tol=ABS_TOL)


def compare_values(expected: object, actual: object, where: str = "$") -> Mismatch | None:
    """The first difference between two decoded JSON values, or ``None``.

    Floats agree within the tolerance; an int matches only an equal int (counts, ids and
    nanosecond times are exact); a bool is never a number; strings, ``None``, keys (and their
    order) and list lengths match exactly.
    """
    if isinstance(expected, bool) or isinstance(actual, bool) or expected is None \
            or actual is None or isinstance(expected, str) or isinstance(actual, str):
        return None if type(expected) is type(actual) and expected == actual \
            else Mismatch(where, expected, actual)
    if isinstance(expected, float) or isinstance(actual, float):
        if isinstance(expected, (int, float)) and isinstance(actual, (int, float)) \
                and type(expected) is type(actual) and _numbers_agree(expected, actual):
            return None
        return Mismatch(where, expected, actual)
    if isinstance(expected, int) or isinstance(actual, int):
        return None if type(expected) is type(actual) and expected == actual \
            else Mismatch(where, expected, actual)
    if isinstance(expected, dict) and isinstance(actual, dict):
        if list(expected) != list(actual):
            return Mismatch(f"{where} (keys)", list(expected), list(actual))
        for key, value in expected.items():
            found = compare_values(value, actual[key], f"{where}.{key}")
            if found is not None:
                return found
        return None
    if isinstance(expected, list) and isinstance(actual, list):
        if len(expected) != len(actual):
            return Mismatch(f"{where} (length)", len(expected), len(actual))
        for index, (left, right) in enumerate(zip(expected, actual)):
            found = compare_values(left, right, f"{where}[{index}]")
            if found is not None:
                return found
        return None
    return Mismatch(where, expected, actual)


def _strict_json(text: str) -> object:
    def refuse(constant: str) -> object:
        raise ValueError(f"non-standard JSON constant {constant}")

    return json.loads(text, parse_constant=refuse)


def compare_json(expected: bytes, actual: bytes) -> Mismatch | None:
    """Compare two JSON documents (a command's ``--json``/``--format json`` output)."""
    try:
        produced = _strict_json(actual.decode())
    except ValueError as error:
        return Mismatch("$ (not strict JSON)", "a JSON document", str(error))
    return compare_values(_strict_json(expected.decode()), produced)


def _cell(text: str) -> object:
    try:
        return _strict_json(text)
    except ValueError:
        return text


def compare_trace(expected: bytes, actual: bytes) -> Mismatch | None:
    """Compare two CSV traces row by row: the header, the number and order of rows, and
    ``TRACE_EXACT_COLUMNS`` exactly; each ``value`` cell (JSON) with ``compare_values``."""
    reference = list(csv.reader(io.StringIO(expected.decode())))
    produced = list(csv.reader(io.StringIO(actual.decode())))
    if not reference or not produced or reference[0] != produced[0]:
        return Mismatch("header", reference[:1], produced[:1])
    header = reference[0]
    if len(reference) != len(produced):
        return Mismatch("rows", len(reference) - 1, len(produced) - 1)
    for number, (left, right) in enumerate(zip(reference[1:], produced[1:]), start=1):
        if len(left) != len(right):
            return Mismatch(f"row {number} (cells)", left, right)
        for column, expected_cell, actual_cell in zip(header, left, right):
            if column in TRACE_EXACT_COLUMNS:
                if expected_cell != actual_cell:
                    return Mismatch(f"row {number}, {column}", expected_cell, actual_cell)
                continue
            found = compare_values(_cell(expected_cell), _cell(actual_cell),
                                   f"row {number}, {column}")
            if found is not None:
                return found
    return None
