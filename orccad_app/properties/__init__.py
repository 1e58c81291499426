"""Properties judged on runs: every ``property`` of a mission evaluated on one run (LTL ones
by runtime monitors from the checker's formulas, signal ones by the linear STL evaluator of ``verify.stl``), for ``orccad run`` and
campaigns. Above the mission and executive layers, below the commands."""

from orccad_app.properties.evaluate import (PropertyKind, PropertyMonitor, PropertyResult,
                                            Verdict, results_dict)

__all__ = ["PropertyMonitor", "PropertyResult", "PropertyKind", "Verdict", "results_dict"]
