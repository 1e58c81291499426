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


def _mission(tmp_path, shipped: str, old: str, new: str) -> str:
    text = (ROOT / "missions" / shipped).read_text(encoding="utf-8")
    assert old in text
    path = tmp_path / shipped
    path.write_text(text.replace(old, new), encoding="utf-8")
    return str(path)


def test_a_zero_minimum_inter_arrival_time_is_refused_not_replaced_by_the_default(tmp_path):
    # it was read as "no clause": the module kind's default period (5 ms) was used instead
    for written in ("0 ms", "0.000001 ms"):
        path = _mission(tmp_path, "arm_interrupts.orc", "sporadic min_interarrival 2 ms",
                        f"sporadic min_interarrival {written}")
        _refused(run_orccad(["tcs", path, "-t", "TrackWatched"]),
                 "arm_interrupts.orc:21:", "minimum inter-arrival time must be at least 1 us")


def test_an_argument_given_twice_is_refused_not_the_last_one_kept(tmp_path):
    cases = [("robot arm : arm3dof;", "robot arm : arm3dof(noise_std = 1e-4, noise_std = 1e-3);",
              "argument 'noise_std' of 'arm3dof' is given twice"),
             ("tracking_error(max = 0.02)", "tracking_error(max = 0.02, max = 0.5)",
              "argument 'max' of 'tracking_error' is given twice"),
             ("law pid(kp = 100.0,", "law pid(kp = 100.0, kp = 1.0,",
              "argument 'kp' of 'pid' is given twice")]
    for old, new, message in cases:
        path = _mission(tmp_path, "arm_retune.orc", old, new)
        _refused(run_orccad(["compile", path]), "arm_retune.orc:", message)


def test_check_refuses_json_with_its_text_only_views():
    # --replay and --observe printed text although --json asked for a JSON document
    source = str(ROOT / "missions" / "false_property.orc")
    _refused(run_orccad(["check", source, "--replay", "placed_after_approach", "--json"]),
             "--replay prints text, not JSON")
    _refused(run_orccad(["check", source, "--observe", "Placed", "--json"]),
             "--observe prints text, not JSON")
