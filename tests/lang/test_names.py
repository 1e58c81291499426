"""check(): interfaces, resolved name kinds, condition kinds, collected errors."""

from __future__ import annotations

import pytest

from orccad_app.diagnostics import OrccadError
from orccad_app.lang import ast, check, diagnose, parse
from orccad_app.lang.names import ConditionKind, NameKind
from tests.lang import examples


def checked(text: str):
    return check(parse(text, "n.orc"))


def test_the_whole_reference_file_checks():
    result = checked(examples.WHOLE_FILE)
    assert set(result.interfaces) == {"ArmDemo", "ABRO"}


def test_interface_lists_file_then_mission_signals_in_declaration_order():
    result = checked("input Stop;\noutput Alarm : string;\n"
                     "mission M { input A, Battery : float; output Done; pause; }\n"
                     "mission N { output O; pause; }\n")
    m = result.interface("M")
    assert [(s.name, s.type) for s in m.inputs] == [("Stop", None), ("A", None),
                                                     ("Battery", "float")]
    assert [s.name for s in m.outputs] == ["Alarm", "Done"]
    assert [s.name for s in result.interface("N").inputs] == ["Stop"]
    assert m.signal("Battery").valued and m.signal("Nope") is None


def test_local_signals_are_not_in_the_interface():
    result = checked("mission M { output O; signal S { emit S; emit O; } }")
    assert [s.name for s in result.interface("M").outputs] == ["O"]


def test_condition_kinds_and_name_kinds_are_resolved():
    result = checked(
        "mission M { input A, B : float; var x := 0;\n"
        "if A { } if ?B < 1.0 { } if x > 2 { } await (A or A); every 2 s { x := x + 1; } }")
    ifs = [s for s in result.program.missions[0].body.statements]
    if_a, if_b, if_x, await_a, every = ifs[1:]
    assert result.condition_kind(if_a.condition) is ConditionKind.SIGNAL
    assert result.condition_kind(if_b.condition) is ConditionKind.DATA
    assert result.condition_kind(if_x.condition) is ConditionKind.DATA
    assert result.condition_kind(await_a.condition) is ConditionKind.SIGNAL
    assert result.kind_of(if_a.condition) is NameKind.SIGNAL
    assert result.kind_of(if_x.condition.left) is NameKind.VARIABLE
    assert every.trigger.condition is None


def test_boolean_variable_condition_is_data():
    result = checked("mission M { var go := true; if go { } if not go { } }")
    _, if_go, if_not = result.program.missions[0].body.statements
    assert result.condition_kind(if_go.condition) is ConditionKind.DATA
    assert result.condition_kind(if_not.condition) is ConditionKind.DATA


def test_all_errors_are_reported_the_first_raised_with_the_rest_as_notes():
    text = "mission M {\n  emit A;\n  await B;\n  exit T;\n}"
    with pytest.raises(OrccadError) as caught:
        checked(text)
    error = caught.value
    assert error.message == "undeclared signal 'A'"
    assert (error.location.line, error.location.col) == (2, 8)
    assert [n.message for n in error.notes] == ["undeclared signal 'B'",
                                                "'exit T' is not inside a trap named 'T'"]
    assert [e.message for e in diagnose(parse(text, "n.orc"))][0] == "undeclared signal 'A'"


def test_undeclared_signal_rendering():
    text = "mission ABRO {\n    input A, B;\n    output O;\n    await C;\n}\n"
    error = diagnose(parse(text, "missions/abro.orc"))[0]
    assert error.format(text).splitlines() == [
        "missions/abro.orc:4:11: error: undeclared signal 'C'",
        "        await C;",
        "              ^",
    ]


def test_duplicate_missions_and_robots():
    errors = diagnose(parse("robot a : k; robot a : k; mission M { } mission M { }", "d.orc"))
    assert [e.message for e in errors] == ["duplicate robot 'a'", "duplicate mission 'M'"]
    assert errors[0].notes[0].message == "previous declaration here"


def test_mission_signal_clashing_with_a_file_signal():
    errors = diagnose(parse("output Done;\nmission M { output Done; emit Done; }", "d.orc"))
    assert len(errors) == 1 and "already declared at file level" in errors[0].message
    assert errors[0].notes[0].location.line == 1


def test_external_tasks_make_run_checked():
    program = parse("mission M { run Home(); run Nope(); }", "t.orc")
    assert diagnose(program) == []  # no Robot-Task known: run is not checked
    library = parse("robot arm : k; robottask Home() on arm { }", "lib.orc").robottasks
    assert [e.message for e in diagnose(program, library)] == ["unknown Robot-Task 'Nope'"]


def test_classify_condition_is_exported():
    from orccad_app.lang import classify_condition
    cond = parse("mission M { if S and T { } }", "c.orc").missions[0].body.statements[0]
    kinds = {"S": NameKind.SIGNAL, "T": NameKind.SIGNAL}
    assert classify_condition(cond.condition, kinds) is ConditionKind.SIGNAL
    assert isinstance(cond.condition, ast.Binary)
