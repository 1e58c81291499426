"""Syntax errors: a named message at the exact place, rendered file:line:col + caret."""

from __future__ import annotations

import pytest

from orccad_app.diagnostics import OrccadError
from orccad_app.lang.parser import parse


def error_of(text: str) -> OrccadError:
    with pytest.raises(OrccadError) as caught:
        parse(text, "e.orc")
    return caught.value


def where(error: OrccadError) -> tuple[int, int]:
    return (error.location.line, error.location.col)


def test_missing_semicolon_points_after_the_statement():
    error = error_of("mission M {\n  emit S\n  pause;\n}")
    assert error.message == "expected ';' after statement"
    assert where(error) == (2, 9)


def test_missing_semicolon_before_closing_brace():
    error = error_of("mission M { await A }")
    assert error.message == "expected ';' after statement" and where(error) == (1, 20)


def test_missing_semicolon_after_a_declaration():
    error = error_of("input A\nmission M { }")
    assert error.message == "expected ';' after declaration" and where(error) == (1, 8)


def test_missing_semicolon_in_a_robottask():
    error = error_of("robottask T() on arm {\n  duration 2 s\n  law pid();\n}")
    assert error.message == "expected ';' after declaration" and where(error) == (2, 15)


def test_unclosed_brace_at_end_of_file_points_at_the_brace():
    error = error_of("mission M {\n  loop {\n    pause;\n\n")
    assert error.message.startswith("unclosed '{'")
    assert where(error) == (2, 8)


def test_unclosed_brace_before_the_next_mission():
    error = error_of("mission M {\n  pause;\nmission N { }")
    assert error.message.startswith("unclosed '{'") and where(error) == (1, 11)


def test_unmatched_closing_brace():
    error = error_of("mission M { pause; }\n}")
    assert error.message == "unmatched '}'" and where(error) == (2, 1)


@pytest.mark.parametrize("text, message, position", [
    ("mision M { }", "unknown keyword 'mision'; did you mean 'mission'?", (1, 1)),
    ("mission M { emti S; }", "unknown statement 'emti'; did you mean 'emit'?", (1, 13)),
    ("mission M { awiat S; }", "unknown statement 'awiat'; did you mean 'await'?", (1, 13)),
    ("mission M { if S { } els { } }", "unknown statement 'els'; did you mean 'else'?",
     (1, 22)),
    ("robottask T() on arm { modul m : k; }", "unknown keyword 'modul'; did you mean "
     "'module'?", (1, 24)),
    ("property M.p: alwyas S;", "unknown keyword 'alwyas'; did you mean 'always'?", (1, 15)),
    ("mission M { duration 2 s; }", "'duration' cannot start a statement here", (1, 13)),
])
def test_misspelt_keywords_get_a_suggestion(text, message, position):
    error = error_of(text)
    assert error.message == message and where(error) == position


def test_unexpected_end_of_file():
    error = error_of("robot arm : arm3dof")
    assert error.message.startswith("unexpected end of file") and where(error) == (1, 20)
    assert parse("// nothing\n", "empty.orc").items == ()  # an empty file is valid


@pytest.mark.parametrize("text, position", [
    ("mission M { run T() within 5 sec; }", (1, 30)),
    ("mission M { await 2.5 secs; }", (1, 23)),
    ("robottask T() on arm { module m : k period 2 seconds; }", (1, 46)),
    ("robottask T() on arm { duration 4 min; }", (1, 35)),
])
def test_bad_duration_unit(text, position):
    error = error_of(text)
    assert error.message.startswith("bad duration unit") and where(error) == position
    assert "s, ms, us, ns" in error.message


def test_duration_finer_than_a_nanosecond():
    error = error_of("mission M { await 1.5 ns; }")
    assert "whole number of nanoseconds" in error.message and where(error) == (1, 19)


def test_missing_duration_unit():
    error = error_of("mission M { run T() within 5; }")
    assert error.message.startswith("expected a duration") and where(error) == (1, 28)


@pytest.mark.parametrize("protocol, hint", [
    ("asyn/sync", "did you mean 'asyn/syn'?"),
    ("syn/synF", "did you mean"),
    ("foo/bar", "one of asyn/asyn"),
])
def test_unknown_protocol(protocol, hint):
    error = error_of(f"robottask T() on arm {{\n  connect a.b -> c.d : {protocol};\n}}")
    assert error.message.startswith(f"unknown protocol '{protocol}'") and hint in error.message
    assert where(error) == (2, 24)
    assert error.location.end_col == 24 + len(protocol)


@pytest.mark.parametrize("protocol", ["asyn/asyn", "syn/syn", "asyn/syn", "syn/asyn",
                                      "asyn/synF", "synF/asyn", "asyn/synD", "asyn/synDF"])
def test_every_protocol_is_known(protocol):
    task = parse(f"robottask T() on arm {{ connect a.b -> c.d : {protocol}; }}",
                 "p.orc").robottasks[0]
    assert task.connections[0].protocol == protocol


def test_unterminated_string_and_comment():
    error = error_of('mission M { emit S("abc); }')
    assert error.message == "unterminated string" and where(error) == (1, 20)
    error = error_of("mission M { pause; /* never closed\n}")
    assert error.message.startswith("unterminated comment") and where(error) == (1, 20)


def test_unexpected_character():
    error = error_of("mission M { await @; }")
    assert error.message == "unexpected character '@'" and where(error) == (1, 19)


def test_unexpected_token_names_what_was_expected():
    error = error_of("mission M { emit S(1 2); }")
    assert error.message == "unexpected '2'; expected ')'" and where(error) == (1, 22)
    error = error_of("mission M { x := 1 + ; }")
    assert error.message == "unexpected ';'; expected an expression"


def test_duplicate_robottask_items_and_clauses():
    error = error_of("robottask T() on arm {\n  law a();\n  law b();\n}")
    assert error.message == "duplicate 'law' in robottask 'T'" and where(error) == (3, 3)
    error = error_of("robottask T() on arm { module m : k period 1 ms period 2 ms; }")
    assert error.message == "duplicate 'period' in module 'm'"


def test_rendered_with_file_line_column_and_caret():
    text = "mission M {\n    emit S\n}\n"
    rendered = error_of(text).format(text)
    assert rendered.splitlines() == [
        "e.orc:2:11: error: expected ';' after statement",
        "        emit S",
        "              ^",
    ]
