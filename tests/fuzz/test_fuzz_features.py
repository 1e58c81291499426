"""Fuzzing of the second-round constructs (tests/fuzz/features.py): imports, run-time
arguments, adjust expressions and ramps, sporadic clauses, automaton placement, robot
parameters, generated and then mutated, through compile, check, tcs and a short run. The
default run takes seconds; ``-m fuzz_long`` runs many more examples."""

from __future__ import annotations

from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings

from tests.fuzz.features import LIBRARY, feature_programs
from tests.fuzz.harness import check_outcome, run_orccad, scratch_folder
from tests.fuzz.missions import mutated


def _settings(examples: int):
    return settings(max_examples=examples, deadline=None, database=None,
                    suppress_health_check=list(HealthCheck))


def _folder(main: str, library: str) -> Path:
    folder = scratch_folder("orccad-fuzz-features-")
    (folder / "m.orc").write_text(main, encoding="utf-8", errors="replace")
    (folder / "lib.orc").write_text(library, encoding="utf-8", errors="replace")
    return folder


def _through_commands(main: str, library: str, run: bool) -> None:
    folder = _folder(main, library)
    source = str(folder / "m.orc")
    check_outcome(run_orccad(["compile", source, "--format", "json"]), json_doc=True)
    check_outcome(run_orccad(["tcs", source, "-t", "T", "--format", "json"]), json_doc=True)
    check_outcome(run_orccad(["check", source, "--replay", "ends",
                              "--counterexample", str(folder / "cex.in")]))
    if run:
        argv = ["run", source, "--json", "--until", "0.1", "--inject", "Gain(250.0)@0.01",
                "--trace", str(folder / "t.csv")]
        check_outcome(run_orccad(argv, budget_s=60), json_doc=True, budget_s=60)


def _generated(examples: int, run: bool):
    @_settings(examples)
    @given(feature_programs())
    def go(files):
        _through_commands(*files, run=run)
    return go


def _mutated(examples: int):
    @_settings(examples)
    @given(mutated(feature_programs().map(lambda files: files[0])))
    def go(main):
        _through_commands(main, LIBRARY, run=False)
    return go


def test_generated_feature_programs_keep_the_promises():
    _generated(12, run=False)()


def test_mutated_feature_programs_keep_the_promises():
    _mutated(12)()


def test_generated_feature_programs_run_in_the_executive():
    _generated(3, run=True)()


@pytest.mark.fuzz_long
def test_long_generated_feature_programs():
    _generated(300, run=False)()


@pytest.mark.fuzz_long
def test_long_mutated_feature_programs():
    _mutated(400)()


@pytest.mark.fuzz_long
def test_long_generated_feature_programs_run():
    _generated(40, run=True)()
