"""Strict JSON for every machine-readable output (``--json``, ``--jsonl``, ``--format json``).

JSON has no NaN or infinity; Python's :mod:`json` writes them as ``NaN``/``Infinity``, which
strict parsers (JavaScript's ``JSON.parse``, ``json.loads(..., parse_constant=reject)``)
refuse. Here a non-finite number is written as ``null`` (documented in ``docs/limits.md``:
"no value", e.g. an unbounded joint limit or a response time that is not bounded), and
:func:`dumps` passes ``allow_nan=False`` so that nothing non-finite can slip through.

>>> dumps({"low": float("-inf"), "x": [1.5, float("nan")], "t": (1, 2)})
'{"low": null, "x": [1.5, null], "t": [1, 2]}'
"""

from __future__ import annotations

import json
import math
from typing import Any

__all__ = ["plain", "dumps"]


def plain(value: Any) -> Any:
    """``value`` with non-finite floats as ``None``, tuples/sets and arrays as lists, numpy
    scalars as Python numbers and mapping keys as strings."""
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if value is None or isinstance(value, (str, bool, int)):
        return value
    if isinstance(value, dict):
        return {str(k): plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [plain(v) for v in value]
    if isinstance(value, (set, frozenset)):
        return [plain(v) for v in sorted(value, key=repr)]
    if hasattr(value, "tolist"):  # numpy arrays and scalars
        return plain(value.tolist())
    if hasattr(value, "__float__"):
        return plain(float(value))
    return str(value)


def dumps(value: Any, **options: Any) -> str:
    """Strict JSON text of ``value`` (see the module docstring); ``options`` as json.dumps."""
    return json.dumps(plain(value), allow_nan=False, **options)
