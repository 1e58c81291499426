"""One grammar and one wording for typed literals (issue 36): an input script's ``S(TEXT)``,
``--inject S(TEXT)@T``, the terminal UI's value field, ``--set ROBOT.PARAM=TEXT`` and a
campaign spec's numbers give the same value, or the same refusal, for the same text."""

from __future__ import annotations

from typing import Any

import pytest

from orccad_app.campaign.distributions import DistributionError, parse_distribution
from orccad_app.diagnostics import OrccadError
from orccad_app.lang.literals import LiteralError, parse_literal, read_literal, typed_value
from orccad_app.mission.injection import parse_injection, typed_injection
from orccad_app.mission.overrides import parse_set
from orccad_app.reactive import ir
from orccad_app.reactive.script import parse_script
from orccad_app.tui.session import parse_value

TEXTS = ["3", "-2", "2.5", "1e-3", " 4 ", "1_000", "nan", "inf", "1e400", "abc", "", "true",
         "false", "yes", "1", "[1, 2.5]", "[]", "[1,,2]", "[1, 2", "1, 2", "[nan]", '"dock"',
         "9" * 30, "9223372036854775808", "-9223372036854775808"]
TYPES = ["bool", "int", "float", "duration", "vector", "string"]


def _answer(call) -> tuple[str, Any]:
    try:
        return "value", call()
    except (OrccadError, ValueError) as error:
        message = getattr(error, "message", str(error))
        return "refused", message.split(": ", 1)[1] if message.startswith("--") else message


def _script(text: str, type_name: str) -> tuple[str, Any]:
    decl = ir.SignalDecl("S", ir.INPUT, type_name)
    return _answer(lambda: parse_script(f"S({text})\n", "s.in", (decl,))[0].inputs["S"])


def _inject(text: str, type_name: str) -> tuple[str, Any]:
    decl = ir.SignalDecl("S", ir.INPUT, type_name)
    return _answer(lambda: typed_injection(parse_injection(f"S({text})@1"), decl).value)


def _console(text: str, type_name: str) -> tuple[str, Any]:
    return _answer(lambda: parse_value(text, type_name, "S"))


@pytest.mark.parametrize("type_name", TYPES)
def test_scripts_injections_and_the_console_agree_on_every_typed_literal(type_name):
    for text in TEXTS:
        if ")" in text or "@" in text:
            continue
        script, inject, console = (_script(text, type_name), _inject(text, type_name),
                                   _console(text, type_name))
        assert script == inject == console, (text, type_name)
        if script[0] == "refused":
            assert script[1] == f"'{text.strip()}' is not a {type_name} value for S" + (
                "" if type_name in ("bool", "string") else script[1][script[1].rfind(" ("):])


def _set(text: str) -> tuple[str, Any]:
    return _answer(lambda: parse_set(f"arm.p={text}").value)


def _campaign(text: str) -> tuple[str, Any]:
    try:
        return "value", parse_distribution(text).args[0]
    except DistributionError as error:
        return "refused", str(error)


@pytest.mark.parametrize("text", ["3", "-2", "2.5", "1e-3", "1_000", "nan", "inf", "1e400",
                                  "abc", "9" * 30])
def test_set_and_campaign_numbers_read_as_every_front_end(text):
    """``--set`` and a spec's numbers take the same numbers, with the same refusal: a
    number is an int when written as one, else a finite float."""
    expected = _answer(lambda: read_literal(text, "number"))
    assert _campaign(text) == expected
    set_kind, set_value = _set(text)
    assert set_kind == expected[0]
    if set_kind == "value":
        assert set_value == expected[1] and type(set_value) is type(expected[1])
    else:
        assert set_value == expected[1].replace("number value", "scalar value").replace(
            "(a finite number)", "(a finite number, true or false)")


def test_the_wording_names_the_type_the_signal_and_what_fits():
    with pytest.raises(LiteralError) as caught:
        read_literal("lots", "float", "Gripper")
    assert caught.value.message == "'lots' is not a float value for Gripper (a finite number)"
    assert parse_literal("[1, 2]") == (1.0, 2.0) and parse_literal("3") == 3
    assert typed_value(3, "float") == 3.0 and type(typed_value(3, "float")) is float
    with pytest.raises(LiteralError, match="'true' is not a int value for N"):
        typed_value(True, "int", "N")
