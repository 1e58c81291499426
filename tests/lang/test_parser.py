"""parse(): the reference examples, every statement form, positions, robustness."""

from __future__ import annotations

import math

import pytest
from hypothesis import HealthCheck, given, settings, strategies as st
from hypothesis.extra.lark import from_lark
from lark import Lark

from orccad_app.diagnostics import OrccadError
from orccad_app.lang import ast
from orccad_app.lang.parser import grammar_lark, grammar_text, keywords, parse
from tests.lang import examples


def statements(body: str) -> tuple:
    return parse("mission M {\n" + body + "\n}\n", "m.orc").missions[0].body.statements


def one(body: str):
    (stmt,) = statements(body)
    return stmt


def expr(text: str) -> ast.Expr:
    return one(f"x := {text};").value


# ------------------------------------------------------------------ the reference examples

@pytest.mark.parametrize("name", sorted(examples.ALL))
def test_every_reference_example_parses(name):
    program = parse(examples.ALL[name], f"{name}.orc")
    assert program.items


def test_declarations_example():
    program = parse(examples.DECLARATIONS, "d.orc")
    arm, auv = program.robots
    assert (arm.name, arm.type, arm.args) == ("arm", "arm3dof", ())
    assert auv.args[0].name == "battery_wh" and auv.args[0].value.value == 400.0
    signals = [(s.name, s.direction.value, s.type) for s in program.signals]
    assert signals == [("Start", "input", None), ("Stop", "input", None),
                       ("Leak", "input", None), ("Battery", "input", "float"),
                       ("Done", "output", None), ("Alarm", "output", "string")]


def test_abro_example_structure():
    (mission,) = parse(examples.ABRO, "abro.orc").missions
    assert [s.name for s in mission.signals] == ["A", "B", "R", "O"]
    (loop,) = mission.body.statements
    assert isinstance(loop, ast.Loop) and loop.each.condition == ast.Name(
        name="R", loc=loop.each.condition.loc)
    par, emit, halt = loop.body.statements
    assert isinstance(par, ast.Par) and len(par.branches) == 2
    assert par.branches[1].statements[0].condition.name == "B"
    assert (emit.signal, type(halt)) == ("O", ast.Halt)


def test_arm_demo_example_structure():
    mission = parse(examples.ARM_DEMO, "a.orc").mission("ArmDemo")
    run_home, repeat, emit = mission.body.statements
    assert (run_home.task, run_home.args, run_home.within_ns) == ("Home", (), None)
    assert repeat.count.value == 3
    (try_,) = repeat.body.statements
    run = try_.body.statements[0]
    assert run.within_ns == 10 * 10**9 and run.args[0].name == "kp"
    assert try_.catches[0].exceptions == ("TrackingLost",)


def test_property_examples():
    props = parse(examples.PROPERTIES, "p.orc").properties
    assert [(p.mission, p.name) for p in props] == [
        ("ArmDemo", "no_overlap"), ("ArmDemo", "recovers"), ("ABRO", "o_needs_a")]
    first = props[0].formula
    assert first.op == "always" and first.operand.op == "not"
    assert first.operand.operand.left == ast.FPredicate(
        predicate="active", argument="TrackPID", loc=first.operand.operand.left.loc)
    implies = props[2].formula.operand
    assert implies.op == "->" and implies.right.op == "once"


def test_items_keep_source_order():
    program = parse(examples.WHOLE_FILE, "all.orc")
    kinds = [type(i).__name__ for i in program.items]
    assert kinds[:2] == ["Robot", "Robot"] and kinds[-3:] == ["Property"] * 3
    assert [m.name for m in program.missions] == ["ArmDemo", "ABRO"]
    assert program.robottask("Home").duration_ns == 2 * 10**9


# ------------------------------------------------------------------ statements

def test_simple_statements():
    nothing, pause, halt = statements("nothing; pause; halt;")
    assert (type(nothing), type(pause), type(halt)) == (ast.Nothing, ast.Pause, ast.Halt)


def test_emit_and_sustain():
    emit, valued, sustain, sustain_valued = statements(
        "emit S; emit V(1 + 2); sustain S; sustain V(?W);")
    assert (emit.signal, emit.value) == ("S", None)
    assert valued.value.op == "+"
    assert isinstance(sustain, ast.Sustain) and sustain.value is None
    assert sustain_valued.value == ast.LastValue(signal="W", loc=sustain_valued.value.loc)


@pytest.mark.parametrize("text, immediate, count, duration_ns, condition", [
    ("await S;", False, None, None, "S"),
    ("await immediate S;", True, None, None, "S"),
    ("await 3 S;", False, 3, None, "S"),
    ("await 2.5 s;", False, None, 2_500_000_000, None),
    ("await 1.5 ms;", False, None, 1_500_000, None),
    ("await 250 us;", False, None, 250_000, None),
    ("await 10 ns;", False, None, 10, None),
    ("await 1e-3 s;", False, None, 1_000_000, None),
    ("await 2s;", False, None, 2_000_000_000, None),
])
def test_await_forms(text, immediate, count, duration_ns, condition):
    stmt = one(text)
    assert isinstance(stmt, ast.Await)
    assert stmt.immediate is immediate and stmt.duration_ns == duration_ns
    assert (stmt.count.value if stmt.count else None) == count
    assert (stmt.condition.name if condition else stmt.condition) == condition


def test_await_signal_expressions():
    either, both = statements("await (S or T); await (S and not T);")
    assert either.condition.op == "or"
    assert both.condition.op == "and" and both.condition.right.op == "not"
    counted = one("await 2 (S or T);")
    assert counted.count.value == 2 and counted.condition.op == "or"


def test_unit_letter_only_makes_a_duration_on_its_own():
    counted = one("await 3 s_ready;")
    assert counted.count.value == 3 and counted.condition.name == "s_ready"


def test_run_forms():
    plain, bare, within = statements("run Home(); run Park; run Track(1.0, kp = 2) within 5 s;")
    assert (plain.task, plain.args) == ("Home", ())
    assert bare.task == "Park" and bare.args == ()
    assert within.within_ns == 5 * 10**9
    assert [a.name for a in within.args] == [None, "kp"]


def test_if_else_and_else_if():
    plain = one("if S { emit A; }")
    assert plain.orelse is None and plain.condition.name == "S"
    chain = one("if ?B < 20.0 { emit A; } else if x > 2 { pause; } else { halt; }")
    assert chain.condition.op == "<" and isinstance(chain.condition.left, ast.LastValue)
    (inner,) = chain.orelse.statements
    assert isinstance(inner, ast.If) and inner.condition.op == ">"
    assert isinstance(inner.orelse.statements[0], ast.Halt)


def test_loops_repeat_every():
    loop, each, repeat, every_sig, every_time = statements(
        "loop { pause; } loop { pause; } each R; repeat n { pause; } "
        "every S { emit A; } every 1 s { emit A; }")
    assert loop.each is None and each.each.condition.name == "R"
    assert repeat.count.name == "n"
    assert every_sig.trigger.condition.name == "S"
    assert every_time.trigger.duration_ns == 10**9 and every_time.trigger.condition is None


def test_preemption_forms():
    strong, handler, immediate, weak, weak_do, suspend = statements(
        "abort { halt; } when S; abort { halt; } when S do { emit A; } "
        "abort { halt; } when immediate S; weak abort { halt; } when S; "
        "weak abort { halt; } when 2 s do { pause; }; suspend { halt; } when S;")
    assert not strong.weak and strong.handler is None and not strong.trigger.immediate
    assert isinstance(handler.handler.statements[0], ast.Emit)
    assert immediate.trigger.immediate
    assert weak.weak and weak.handler is None
    assert weak_do.weak and weak_do.trigger.duration_ns == 2 * 10**9
    assert isinstance(suspend, ast.Suspend) and suspend.trigger.condition.name == "S"


def test_trap_and_exit():
    plain, handled = statements("trap T { exit T; } trap U { pause; } handle { halt; }")
    assert plain.name == "T" and plain.handler is None
    assert plain.body.statements[0] == ast.Exit(name="T", loc=plain.body.statements[0].loc)
    assert isinstance(handled.handler.statements[0], ast.Halt)


def test_try_catches():
    stmt = one("try { run A(); } catch E1, E2 { pause; } catch E3 { halt; }")
    assert [c.exceptions for c in stmt.catches] == [("E1", "E2"), ("E3",)]


def test_par_and_race():
    par, race, single = statements(
        "par { pause; } || { halt; } || { nothing; } race { pause; } || { halt; } par { }")
    assert len(par.branches) == 3 and len(race.branches) == 2
    assert isinstance(race, ast.Race) and len(single.branches) == 1


def test_local_signals_pure_and_valued():
    stmt = one("signal S, T : float { emit T(1.0); }")
    assert [(s.name, s.type, s.direction) for s in stmt.signals] == [
        ("S", None, ast.Direction.LOCAL), ("T", "float", ast.Direction.LOCAL)]


def test_variables():
    decl, typed, assign = statements("var x := 0; var t : duration := 2 s; x := x + 1;")
    assert (decl.name, decl.value.value, decl.type) == ("x", 0, None)
    assert typed.type == "duration" and typed.value.duration_ns == 2 * 10**9
    assert assign.name == "x" and assign.value.op == "+"


def test_nested_block_and_mission_declarations_anywhere():
    program = parse("mission M { pause; { emit O; } output O; on fatal { halt; } }", "m.orc")
    mission = program.missions[0]
    assert [s.name for s in mission.signals] == ["O"]
    assert isinstance(mission.body.statements[1], ast.Block)
    assert isinstance(mission.on_fatal.statements[0], ast.Halt)


# ------------------------------------------------------------------ expressions

@pytest.mark.parametrize("text, value", [
    ("3", 3), ("-0.5", -0.5), ("1e-3", 1e-3), ("2.5E+2", 250.0), ("-7", -7)])
def test_numbers(text, value):
    node = expr(text)
    assert isinstance(node, ast.Number) and node.value == value and node.text == text
    assert type(node.value) is type(value)


def test_literals():
    assert expr("pi").value == math.pi
    assert expr('"a \\"b\\"\\n"').value == 'a "b"\n'
    assert expr("true") == ast.Bool(value=True, loc=expr("true").loc)
    vec = expr("[0.5, -1, x]")
    assert [type(i).__name__ for i in vec.items] == ["Number", "Number", "Name"]
    assert expr("[]").items == ()
    assert expr("?Battery").signal == "Battery"
    assert expr("1.5 ms").duration_ns == 1_500_000


@pytest.mark.parametrize("text, shape", [
    ("1 + 2 * 3", ("+", 1, ("*", 2, 3))),
    ("(1 + 2) * 3", ("*", ("+", 1, 2), 3)),
    ("1 - 2 - 3", ("-", ("-", 1, 2), 3)),
    ("8 / 4 / 2", ("/", ("/", 8, 4), 2)),
    ("1 < 2 and 3 >= 4 or 5 != 6", ("or", ("and", ("<", 1, 2), (">=", 3, 4)), ("!=", 5, 6))),
    ("not 1 == 2", ("not", ("==", 1, 2))),
    ("- x * 2", ("*", ("-", "x"), 2)),
    ("1 <= 2 == true", None),
])
def test_precedence(text, shape):
    def walk(node):
        if isinstance(node, ast.Binary):
            return (node.op, walk(node.left), walk(node.right))
        if isinstance(node, ast.Unary):
            return (node.op, walk(node.operand))
        return node.name if isinstance(node, ast.Name) else node.value
    if shape is None:
        with pytest.raises(OrccadError):
            expr(text)
    else:
        assert walk(expr(text)) == shape


def test_call_like_arguments():
    stmt = one("run T(q = [1, 2], traj = cosine(w = pi), 3);")
    assert stmt.args[1].value == ast.Call(func="cosine", args=stmt.args[1].value.args,
                                          loc=stmt.args[1].value.loc)
    assert stmt.args[1].value.arg("w").value.text == "pi"
    assert stmt.args[2].name is None


def test_comments_are_ignored():
    program = parse("// a\nmission /* b \n c */ M { pause; // d\n }", "c.orc")
    assert program.missions[0].name == "M"


# ------------------------------------------------------------------ positions

def test_statement_positions():
    text = "mission M {\n  input A;\n  await A;\n    emit O;\n}\n"
    mission = parse(text, "pos.orc").missions[0]
    await_, emit = mission.body.statements
    assert (await_.loc.file, await_.loc.line, await_.loc.col) == ("pos.orc", 3, 3)
    assert (await_.loc.end_line, await_.loc.end_col) == (3, 11)
    assert (emit.loc.line, emit.loc.col, emit.signal_loc.col) == (4, 5, 10)
    assert (await_.condition.loc.line, await_.condition.loc.col) == (3, 9)
    assert (mission.signals[0].loc.line, mission.signals[0].loc.col) == (2, 9)
    assert (mission.loc.line, mission.loc.col, mission.loc.end_line) == (1, 1, 5)


def test_compound_statement_spans_its_lines():
    stmt = statements("pause;\nloop {\n  pause;\n} each R;")[1]
    assert (stmt.loc.line, stmt.loc.col, stmt.loc.end_line, stmt.loc.end_col) == (3, 1, 5, 10)


def test_run_task_position():
    run = one("  run Home();")
    assert (run.task_loc.line, run.task_loc.col, run.task_loc.end_col) == (2, 7, 11)


# ------------------------------------------------------------------ grammar properties

def test_grammar_is_lalr_and_strict():
    pytest.importorskip("interegular")
    parser = Lark(grammar_text(), parser="lalr", strict=True, propagate_positions=True)
    assert parser.options.parser == "lalr"


def test_keywords_are_reserved_everywhere():
    assert {"mission", "loop", "emit", "await", "abort", "duration", "pi", "true",
            "always", "since", "done"} <= keywords()
    for text in ("mission loop { }", "mission M { emit loop; }", "input done;",
                 "mission M { var pause := 1; }", "mission M { await halt; }"):
        with pytest.raises(OrccadError) as caught:
            parse(text, "k.orc")
        assert "reserved keyword" in caught.value.message


def test_keyword_error_points_at_the_keyword():
    with pytest.raises(OrccadError) as caught:
        parse("mission M {\n  emit loop;\n}", "k.orc")
    loc = caught.value.location
    assert (loc.line, loc.col, loc.end_col) == (2, 8, 12)


def test_deep_nesting_is_an_error_not_a_crash():
    text = "mission M { x := " + "(" * 3000 + "1" + ")" * 3000 + "; }"
    try:
        parse(text, "deep.orc")
    except OrccadError as error:
        assert error.location is not None


_GENERATED = from_lark(grammar_lark(), explicit={
    "DURATION": st.sampled_from(["2 s", "1.5 ms", "250 us", "10ns", "1e-3 s"])})


@settings(max_examples=150, deadline=None, suppress_health_check=list(HealthCheck))
@given(_GENERATED)
def test_grammar_sentences_parse_or_fail_cleanly(text):
    try:
        program = parse(text, "gen.orc")
    except OrccadError as error:
        assert error.location is not None and error.location.line >= 1
    else:
        assert isinstance(program, ast.Program)


@settings(max_examples=150, deadline=None)
@given(st.text(alphabet=st.sampled_from(list("mission M{}();:=|/*\"\n ?<->.,[]0123s")),
               max_size=60))
def test_arbitrary_text_only_ever_raises_orccad_errors(text):
    try:
        parse(text, "noise.orc")
    except OrccadError as error:
        assert error.location is not None


def test_a_keyword_may_name_an_argument_but_nothing_else():
    program = parse("robot arm : arm3dof;\nrobottask T() on arm {\n"
                    "    task_function joint_tracking(trajectory = min_jerk(goal = [0.0], "
                    "duration = 1.0));\n}\n", "k.orc")
    trajectory = program.robottasks[0].task_function.args[0].value
    assert [a.name for a in trajectory.args] == ["goal", "duration"]
    with pytest.raises(OrccadError, match="'loop' is a reserved keyword"):
        parse("mission M { output loop; }", "k.orc")
