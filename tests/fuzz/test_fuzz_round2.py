"""Fuzzing of issue 28's feature areas, in CI: sub-missions run with repetition (the inlining
budget), campaign specs and ``--timing`` overrides. Each generated input is refused with a
located message (exit 2, ``OrccadError``) or accepted, within its budget; never an internal
error, a hang or a silent change."""

from __future__ import annotations

from decimal import Decimal
from pathlib import Path

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from orccad_app.campaign.spec import parse_spec
from orccad_app.diagnostics import OrccadError
from orccad_app.mission.overrides import parse_timing
from orccad_app.reactive.inlining import MAX_INLINED_NODES
from tests.campaign.conftest import LEAK_SPEC
from tests.fuzz.harness import check_outcome, run_orccad, scratch_folder


def _settings(examples: int):
    return settings(max_examples=examples, deadline=None, database=None,
                    suppress_health_check=list(HealthCheck))


def _repeated(depth: int, repeat: int) -> str:
    lines = ["input A;", "output O;", "mission L0 { await A; emit O; }"]
    for level in range(1, depth + 1):
        body = " ".join(f"run mission L{level - 1};" for _ in range(repeat))
        lines.append(f"mission L{level} {{ {body} }}")
    return "\n".join(lines) + "\n"


@_settings(12)
@given(st.integers(1, 9), st.integers(1, 12))
def test_sub_missions_run_with_repetition_stay_within_the_inlining_budget(depth, repeat):
    folder = scratch_folder("orccad-fuzz-inline-")
    path = folder / "m.orc"
    path.write_text(_repeated(depth, repeat), encoding="utf-8")
    outcome = run_orccad(["compile", str(path), "-m", f"L{depth}", "--format", "json"],
                         budget_s=60)
    check_outcome(outcome, json_doc=True, budget_s=60)
    if outcome.status == 2:
        assert "syntax nodes once its sub-missions are inlined" in outcome.err \
            or "states" in outcome.err, outcome.err


_VALUES = st.one_of(st.integers(-2**70, 2**70), st.floats(allow_nan=True),
                    st.sampled_from(["inf", "nan", "-inf", '""', '"U(0, 1)"', '"UI(0, 5)"',
                                     '"choice(1, 2)"', '"N(0, -1)"', '"U(3, 1)"', "true",
                                     "[1, 2]", "{}", '"auv.leak=1@U(8, 12)"',
                                     '"UI(0, 100000000000000000000)"']))
_KEYS = st.sampled_from(["runs", "seed", "until_s", "seeds", "mission", "signals", "bogus"])


def _toml(value) -> str:
    if isinstance(value, float):
        return repr(value) if value == value and abs(value) != float("inf") else "nan"
    return str(value)


@_settings(150)
@given(st.lists(st.tuples(_KEYS, _VALUES), max_size=4, unique_by=lambda kv: kv[0]))
def test_generated_campaign_specs_are_read_or_refused_with_a_location(entries):
    text = LEAK_SPEC
    for key, value in entries:
        lines = [line for line in text.splitlines() if not line.startswith(f"{key} =")]
        text = f"{key} = {_toml(value)}\n" + "\n".join(lines) + "\n"
    try:
        spec = parse_spec(text, "fuzz.toml")
    except OrccadError as error:
        assert error.message
        return
    assert 1 <= spec.runs <= 1_000_000 and 0 <= spec.seed < 2**63
    assert spec.until_s is None or 0 < spec.until_s <= 365 * 24 * 3600


@_settings(200)
@given(st.one_of(st.decimals(allow_nan=False, allow_infinity=False, places=9),
                 st.floats(), st.text(max_size=12)))
def test_generated_timing_overrides_are_exact_or_refused(value):
    text = f"Survey.pilot.wcet_ms={value}"
    try:
        timing = parse_timing(text)
    except OrccadError as error:
        assert error.message
        return
    assert timing.value_ns * Decimal(1) == Decimal(str(value).strip().replace("_", "")) * 10**6


def test_the_inlining_budget_is_the_documented_one():
    limits = (Path(__file__).resolve().parents[2] / "docs" / "limits.md").read_text()
    assert f"{MAX_INLINED_NODES:,}".replace(",", " ") in limits
