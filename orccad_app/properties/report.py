"""The properties' part of the run report, for people."""

from __future__ import annotations

import math

from orccad_app.properties.evaluate import PropertyResult

__all__ = ["format_properties", "format_robustness"]


def format_robustness(result: PropertyResult) -> str:
    """``robustness 4.213 [m]``, ``robustness +inf``, or ``""`` for an LTL property."""
    value = result.robustness
    if value is None:
        return ""
    if math.isinf(value):
        return f"robustness {'+' if value > 0 else '-'}inf (decided by events alone)"
    unit = f" {result.unit}" if result.unit else ""
    return f"robustness {value:.6g}{unit}"


def format_properties(results: list[PropertyResult]) -> list[str]:
    """One line per property: verdict, kind, name, robustness."""
    lines = ["Properties on this run:"]
    for result in results:
        kind = "signal" if result.kind.value == "signal" else "LTL"
        detail = format_robustness(result)
        if result.reason is not None:
            detail = result.reason
        lines.append(f"  {result.verdict.value:<9} {kind:<6} {result.name}"
                     f"{'   ' + detail if detail else ''}")
    return lines
