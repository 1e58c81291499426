"""The transformer's choices: literal folding, else-if, formulas, strings, locations."""

from __future__ import annotations

from orccad_app.lang import ast, parse


def formula(text: str) -> ast.Formula:
    return parse(f"property M.p: {text};", "f.orc").properties[0].formula


def shape(f):
    if isinstance(f, ast.FBinary):
        return (f.op, shape(f.left), shape(f.right))
    if isinstance(f, ast.FUnary):
        return (f.op, shape(f.operand))
    if isinstance(f, ast.FSignal):
        return f.name
    if isinstance(f, ast.FPredicate):
        return f"{f.predicate}({f.argument})"
    if isinstance(f, ast.FStatus):
        return f.status
    return f.value


def test_formula_precedence():
    assert shape(formula("A -> B -> C")) == ("->", "A", ("->", "B", "C"))
    assert shape(formula("A or B and C <-> D")) == (
        "<->", ("or", "A", ("and", "B", "C")), "D")
    assert shape(formula("always A -> B")) == ("->", ("always", "A"), "B")
    assert shape(formula("A until B since C and D")) == (
        "and", ("until", "A", ("since", "B", "C")), "D")
    assert shape(formula("not next eventually never previously once historically A")) == (
        "not", ("next", ("eventually", ("never", ("previously", ("once", (
            "historically", "A")))))))


def test_formula_atoms():
    assert shape(formula("active(T) and started(T) and ended(T) and raised(E)")) == (
        "and", ("and", ("and", "active(T)", "started(T)"), "ended(T)"), "raised(E)")
    assert shape(formula("(done or failed or aborted) and true and not false")) == (
        "and", ("and", ("or", ("or", "done", "failed"), "aborted"), True), ("not", False))


def test_unqualified_property_and_assumption():
    program = parse("property p: true; assume M.q: always A;", "p.orc")
    assert (program.properties[0].mission, program.properties[0].name) == (None, "p")
    assert (program.assumptions[0].mission, program.assumptions[0].name) == ("M", "q")


def test_negative_literals_fold_but_expressions_stay():
    stmts = parse("mission M { x := -2; x := -(1 + 2); x := - -3; }", "n.orc") \
        .missions[0].body.statements
    assert stmts[0].value == ast.Number(value=-2, text="-2", loc=stmts[0].value.loc)
    assert isinstance(stmts[1].value, ast.Unary) and stmts[1].value.op == "-"
    assert isinstance(stmts[2].value, ast.Unary) and stmts[2].value.operand.value == -3


def test_else_if_is_an_else_block_holding_the_if():
    stmt = parse("mission M {\n if A { }\n else if B { } }", "e.orc").missions[0] \
        .body.statements[0]
    (inner,) = stmt.orelse.statements
    assert stmt.orelse.loc == inner.loc and (inner.loc.line, inner.loc.col) == (3, 7)


def test_string_escapes_and_duration_text():
    emit = parse(r'mission M { emit S("tab\there \\ \"q\""); await 2   ms; }', "s.orc") \
        .missions[0].body.statements[0]
    assert emit.value.value == 'tab\there \\ "q"'
    value = parse("mission M { x := 2   ms; }", "d.orc").missions[0].body.statements[0].value
    assert (value.duration_ns, value.text) == (2_000_000, "2 ms")


def test_mission_body_location_spans_its_statements():
    mission = parse("mission M {\n  output O;\n  pause;\n  emit O;\n}", "b.orc").missions[0]
    body = mission.body.loc
    assert (body.line, body.col, body.end_line) == (3, 3, 4)
    empty = parse("mission M { }", "b.orc").missions[0]
    assert empty.body.statements == () and empty.body.loc == empty.loc
