"""Fuzzing in CI (issue 12): generated and mutated missions, scripts and ``--inject`` specs
through every command, in process. The default run has a fixed budget (a few dozen examples per
test, about a minute in all); ``-m fuzz_long`` runs the same properties with hundreds of
examples. Promises checked (tests/fuzz/harness.py): no uncaught exception, no run past its
budget, exit status in {0, 1, 2}, strict JSON."""

from __future__ import annotations

import random
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from tests.fuzz.harness import CORPUS, check_outcome, replay, run_orccad, scratch_folder
from tests.fuzz.missions import inject_specs, missions, mutated, scripts, task_missions

ROOT = Path(__file__).resolve().parents[2]
SHIPPED = sorted((ROOT / "missions").glob("*.orc"))
SCRIPTS = {"abro.orc": "abro.in", "arm_recovery.orc": "arm_recovery.in",
           "auv_survey.orc": "auv_survey.in"}


def _settings(examples: int):
    return settings(max_examples=examples, deadline=None, database=None,
                    suppress_health_check=list(HealthCheck))


def _files(**texts: str) -> Path:
    folder = scratch_folder("orccad-fuzz-")
    for name, text in texts.items():
        (folder / name.replace("_", ".")).write_text(text, encoding="utf-8", errors="replace")
    return folder


def _through_commands(mission: str, script: str) -> None:
    """compile (json), check and react (jsonl) on one mission and script."""
    folder = _files(m_orc=mission, s_in=script)
    source, inputs = str(folder / "m.orc"), str(folder / "s.in")
    check_outcome(run_orccad(["compile", source, "--format", "json"]), json_doc=True)
    check_outcome(run_orccad(["check", source]))
    check_outcome(run_orccad(["react", source, "--inputs", inputs, "--jsonl"]),
                  json_lines=True)


# ---------------------------------------------------------------- well-typed, generated

def _generated(examples: int):
    @_settings(examples)
    @given(missions(), scripts())
    def run(mission, script):
        _through_commands(mission, script)
    return run


def test_generated_missions_keep_the_promises():
    _generated(40)()


def _mutated_generated(examples: int):
    @_settings(examples)
    @given(mutated(missions()), mutated(scripts()))
    def run(mission, script):
        _through_commands(mission, script)
    return run


def test_mutated_generated_missions_keep_the_promises():
    _mutated_generated(50)()


def _runs(examples: int):
    @_settings(examples)
    @given(task_missions(), st.sampled_from(["", "Stop@0.05", "Stop@0", "Stop@1e300"]))
    def run(mission, inject):
        folder = _files(m_orc=mission)
        argv = ["run", str(folder / "m.orc"), "--json", "--until", "0.3",
                "--trace", str(folder / "t.csv")] + (["--inject", inject] if inject else [])
        check_outcome(run_orccad(argv, budget_s=60), json_doc=True, budget_s=60)
    return run


def test_generated_missions_run_in_the_executive():
    _runs(6)()


# ---------------------------------------------------------------- seeded mutations of shipped files

_HOSTILE = ["1e400", "nan", "-1", "0", "9223372036854775808", "\t", "\f", "\u2028", "\ufeff",
            "#", '"', "(", ")", "{", "}", ";", "@", "||", "0 ms", "1e-400", "9" * 60]


def _mutate(rng: random.Random, text: str) -> str:
    for _ in range(rng.randint(1, 4)):
        at = rng.randrange(len(text)) if text else 0
        choice = rng.random()
        if choice < 0.3:
            text = text[:at] + text[at + rng.randint(1, 12):]
        elif choice < 0.5:
            end = min(len(text), at + rng.randint(1, 60))
            text = text[:end] + text[at:end] + text[end:]
        else:
            text = text[:at] + rng.choice(_HOSTILE) + text[at + (choice > 0.8):]
    return text


def _shipped_mutations(seed: int, count: int) -> None:
    rng = random.Random(seed)
    for _ in range(count):
        path = rng.choice(SHIPPED)
        text = _mutate(rng, path.read_text(encoding="utf-8"))
        script_name = SCRIPTS.get(path.name)
        script = (ROOT / "missions" / script_name).read_text() if script_name else ""
        folder = _files(m_orc=text, s_in=_mutate(rng, script) if script else "\n")
        source = str(folder / "m.orc")
        command = rng.choice([["compile", source, "--format", "json"], ["check", source],
                              ["react", source, "--inputs", str(folder / "s.in"), "--jsonl"]])
        check_outcome(run_orccad(command), json_doc="json" in command,
                      json_lines="--jsonl" in command)


def test_seeded_mutations_of_the_shipped_missions():
    _shipped_mutations(seed=12, count=60)


# ---------------------------------------------------------------- every command, briefly

PID = str(ROOT / "missions" / "arm_pid.orc")


@pytest.mark.parametrize("argv, json_doc", [
    (["rta", PID, "--task", "TrackPID", "--format", "json"], True),
    (["tcs", PID, "--task", "TrackPID", "--format", "json"], True),
    (["tcs", PID, "--task", "TrackPID", "--processors", "256"], False),
    (["plugins", "--json"], True),
    (["plugins", "--verbose"], False),
    (["check", str(ROOT / "missions" / "auv_survey.orc")], False),
    (["run", PID, "--json", "--until", "0.05"], True),
])
def test_every_command_keeps_the_promises(argv, json_doc):
    check_outcome(run_orccad(argv), json_doc=json_doc)


def test_a_short_campaign_keeps_the_promises(tmp_path):
    argv = ["campaign", PID, "--spec", str(ROOT / "missions" / "arm_pid.campaign.toml"),
            "--runs", "2", "--until", "0.05", "--workers", "1", "--json",
            "--db", str(tmp_path / "c.db")]
    check_outcome(run_orccad(argv, budget_s=120), json_doc=True, budget_s=120)


def test_a_short_falsification_keeps_the_promises(tmp_path):
    argv = ["falsify", PID, "--spec", str(ROOT / "missions" / "arm_pid.campaign.toml"),
            "-p", "bounded", "--budget", "2", "--until", "0.05", "--workers", "1",
            "--trace", str(tmp_path / "worst.csv")]
    check_outcome(run_orccad(argv, budget_s=120), budget_s=120)


def _injections(examples: int):
    @_settings(examples)
    @given(st.lists(inject_specs(), min_size=1, max_size=2))
    def run(specs):
        argv = ["run", PID, "--json", "--until", "0.03"]
        for spec in specs:
            argv += ["--inject", spec]
        check_outcome(run_orccad(argv), json_doc=True)
    return run


def test_inject_specs_keep_the_promises():
    _injections(8)()


# ---------------------------------------------------------------- the corpus of found cases

@pytest.mark.parametrize("case", sorted(CORPUS.glob("*.json")), ids=lambda p: p.stem)
def test_corpus_case(case, tmp_path):
    check_outcome(replay(case, tmp_path))


# ---------------------------------------------------------------- long runs (-m fuzz_long)

@pytest.mark.fuzz_long
def test_long_generated_missions():
    _generated(400)()


@pytest.mark.fuzz_long
def test_long_mutated_generated_missions():
    _mutated_generated(600)()


@pytest.mark.fuzz_long
def test_long_seeded_mutations_of_the_shipped_missions():
    for seed in range(20):
        _shipped_mutations(seed=seed, count=50)


@pytest.mark.fuzz_long
def test_long_generated_missions_run():
    _runs(60)()


@pytest.mark.fuzz_long
def test_long_inject_specs():
    _injections(100)()
