"""The one report of a run: :class:`RunReport`, rendered as text or JSON by every consumer."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from orccad_app.mission.result import RunResult
from orccad_app.properties.evaluate import PropertyResult, Verdict, results_dict
from orccad_app.properties.report import format_properties
from orccad_app.trace.report import InjectionRecord, format_report, report_dict

__all__ = ["RunReport"]


@dataclass(frozen=True)
class RunReport:
    """What one run gives: its result, what was raised from outside, the properties' verdicts.

    :param result: the executive's :class:`~orccad_app.mission.result.RunResult`.
    :param injections: the inputs and faults raised from outside (``--inject``, a script,
        the console's user), in time order.
    :param properties: every property of the mission judged on this run
        (:class:`~orccad_app.properties.evaluate.PropertyResult`, in declaration order).
    """

    result: RunResult
    injections: tuple[InjectionRecord, ...] = ()
    properties: tuple[PropertyResult, ...] = ()

    @property
    def violated(self) -> tuple[str, ...]:
        """The properties false on this run."""
        return tuple(p.name for p in self.properties if p.verdict is Verdict.FALSE)

    @property
    def exit_status(self) -> int:
        """0 when the mission ended ``done`` and no property is false on the run, else 1."""
        return max(self.result.exit_status, 1 if self.violated else 0)

    def as_dict(self) -> dict[str, Any]:
        """``orccad run --json``'s object (:mod:`orccad_app.trace.report`, and ``properties``:
        :func:`~orccad_app.properties.evaluate.results_dict`)."""
        report = report_dict(self.result, self.injections)
        report["properties"] = results_dict(list(self.properties))
        return report

    def text(self) -> str:
        """``orccad run``'s text report, the properties' verdicts last."""
        lines = [format_report(self.result, self.injections)]
        if self.properties:
            lines += format_properties(list(self.properties))
        return "\n".join(lines)
