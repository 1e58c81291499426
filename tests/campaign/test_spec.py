"""The campaign spec: distributions, its form, and errors located at the spec's line."""

from __future__ import annotations

import numpy as np
import pytest

from orccad_app.campaign.distributions import Kind, parse_distribution
from orccad_app.campaign.spec import parse_spec
from orccad_app.diagnostics import OrccadError
from orccad_app.mission.injection import PlantFault

from .conftest import AUV, LEAK_SPEC, orccad


def test_distributions_draw_inside_their_support_and_round_to_six_digits():
    rng = np.random.default_rng(0)
    uniform = parse_distribution("U(20, 170)")
    draws = [uniform.sample(rng) for _ in range(200)]
    assert all(20 <= d <= 170 for d in draws)
    assert all(len(f"{d:.15g}".replace(".", "").lstrip("0")) <= 6 for d in draws)
    truncated = parse_distribution("N(20, 5, 14, 26)")
    assert all(14 <= truncated.sample(rng) <= 26 for _ in range(200))
    assert parse_distribution("choice(1, 2, 4)").choices == (1, 2, 4)
    assert {parse_distribution("UI(3, 5)").sample(rng) for _ in range(100)} == {3, 4, 5}
    bernoulli = [parse_distribution("B(0.3)").sample(rng) for _ in range(2000)]
    assert abs(np.mean(bernoulli) - 0.3) < 0.05
    assert parse_distribution(2.5).kind is Kind.CONSTANT


@pytest.mark.parametrize("text, message", [
    ("U(3, 1)", "lower bound exceeds"), ("N(0, -1)", "sigma must be > 0"),
    ("Q(1, 2)", "unknown distribution"), ("B(1.5)", "p must be in"),
    ("U(1)", "takes 2 numbers"), ("UI(0.5, 2)", "integer bounds")])
def test_bad_distributions_are_refused_with_a_reason(text, message):
    with pytest.raises(ValueError, match=message):
        parse_distribution(text)


def test_the_spec_is_read_with_its_entries():
    spec = parse_spec(LEAK_SPEC, "leak.toml")
    assert spec.mission == "AuvSurvey" and spec.until_s == 30.0 and spec.seed == 5
    assert [p.target for p in spec.params] == ["auv.cb_height_m"]
    inject, = spec.injections
    assert (inject.name, inject.fault, inject.probability) == (
        "auv.leak", PlantFault("auv", "leak"), 0.3)
    assert inject.time.bounds == (8, 12) and inject.value.args == (1,)
    assert spec.checks[0].below == 30.0


@pytest.mark.parametrize("text, line, message", [
    ("runs = 10\nfoo = 1\n", 2, "unknown key 'foo'"),
    ("[params]\n\"auv.x\" = \"U(2, 1)\"\n", 2, "lower bound exceeds"),
    ("[[inject]]\nevent = \"leak\"\n", 2, "bad event"),
    ("[[inject]]\nevent = \"leak=1@3\"\n", 2, "a plant fault is ROBOT.FAULT"),
    ("[[inject]]\nevent = \"auv.leak.x=1@3\"\n", 2, "a plant fault is ROBOT.FAULT"),
    ("[[inject]]\nevent = \"auv.leak=1@3\"\n[[inject]]\nevent = \"a@1\"\nprobability = 2\n",
     5, "probability must be"),
    ("[[check]]\nname = \"c\"\nmetric = \"depth\"\nbelow = 1\n", 3, "unknown metric"),
    ("runs = [\n", 1, "bad TOML")])
def test_errors_of_form_name_the_line(text, line, message):
    with pytest.raises(OrccadError, match=message) as caught:
        parse_spec(text, "s.toml")
    assert caught.value.location.file == "s.toml"
    assert caught.value.location.line == line


@pytest.mark.parametrize("entry, line, message", [
    ('[params]\n"auv.cb_height_m" = "U(0.01, 0.5)"\n', 4, "must be <= 0.15"),
    ('[params]\n"auv.nope" = 1\n', 4, "declares no parameter 'nope'"),
    ('[timing]\n"Survey.pilot.bcet_ms" = "U(0.5, 3)"\n', 4, "exceeds its WCET"),
    ('[[inject]]\nevent = "auv.leak=1@U(10, 50)"\n', 4, "horizon"),
    ('[[inject]]\nevent = "Nope@U(1, 5)"\n', 4, "not an input"),
    ('signals = ["auv.nope"]\n', 3, "no sensor port 'nope'")])
def test_names_and_bounds_are_checked_against_the_mission(tmp_path, entry, line, message):
    spec = tmp_path / "bad.toml"
    spec.write_text('mission = "AuvSurvey"\nuntil_s = 40\n' + entry, encoding="utf-8")
    result = orccad("campaign", AUV, "--spec", str(spec), "--db", str(tmp_path / "x.db"))
    assert result.returncode == 2, result.stderr
    assert f"{spec}:{line}:" in result.stderr and message in result.stderr
    assert "Traceback" not in result.stderr
