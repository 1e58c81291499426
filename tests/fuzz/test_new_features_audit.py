"""Regressions found by a hostile pass over the features of the plan language's second round
(sub-mission imports, run-time arguments, computed type-1 updates, sporadic Module-Tasks,
automaton placement, robot parameters, counterexample replay): each bad input gets a located
message and exit status 2, never an internal error."""

from __future__ import annotations

from pathlib import Path

from tests.fuzz.harness import check_outcome, run_orccad

ROOT = Path(__file__).resolve().parents[2]


def _refused(outcome, *fragments: str) -> None:
    check_outcome(outcome)
    assert outcome.status == 2, outcome.err
    for fragment in fragments:
        assert fragment in outcome.err, outcome.err


def test_an_import_path_with_a_nul_character_is_refused_at_the_import(tmp_path):
    source = tmp_path / "m.orc"
    source.write_text('from "lib/homing\0.orc" import Homing;\n'
                      "mission M { run mission Homing; }\n", encoding="utf-8")
    _refused(run_orccad(["compile", str(source)]), f"{source}:1:6", "NUL")
