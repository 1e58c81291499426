"""The AST: frozen, hashable, hand-buildable nodes and their helpers."""

from __future__ import annotations

import dataclasses

import pytest

from orccad_app.diagnostics import NOWHERE
from orccad_app.lang import ast


def test_nodes_build_by_keyword_with_a_default_location():
    emit = ast.Emit(signal="O")
    assert emit.loc is NOWHERE and emit.value is None
    with pytest.raises(TypeError):
        ast.Emit("O")  # keyword-only: field order may grow without breaking callers


def test_nodes_are_frozen_and_hashable():
    name = ast.Name(name="S")
    with pytest.raises(dataclasses.FrozenInstanceError):
        name.name = "T"
    assert {ast.Await(trigger=ast.Trigger(condition=name))} == {
        ast.Await(trigger=ast.Trigger(condition=ast.Name(name="S")))}


def test_await_exposes_its_trigger():
    node = ast.Await(trigger=ast.Trigger(condition=ast.Name(name="S"), immediate=True,
                                         count=ast.Number(value=2)))
    assert node.condition.name == "S" and node.immediate and node.count.value == 2
    assert ast.Await(trigger=ast.Trigger(duration_ns=5)).duration_ns == 5


def test_program_views_keep_source_order():
    robot = ast.Robot(name="arm", type="arm3dof")
    task = ast.RobotTask(name="T", params=(), robot="arm")
    m1 = ast.Mission(name="M1", signals=(), body=ast.Block())
    sig = ast.SignalDecl(name="A", direction=ast.Direction.INPUT)
    m2 = ast.Mission(name="M2", signals=(), body=ast.Block())
    prop = ast.Property(mission="M1", name="p", formula=ast.FBool(value=True))
    assume = ast.Assumption(mission=None, name="a", formula=ast.FBool(value=True))
    program = ast.Program(filename="f.orc", items=(robot, m1, sig, task, m2, prop, assume))
    assert program.missions == (m1, m2) and program.signals == (sig,)
    assert program.robots == (robot,) and program.robottasks == (task,)
    assert program.properties == (prop,) and program.assumptions == (assume,)
    assert program.mission("M2") is m2 and program.mission("X") is None
    assert program.robottask("T") is task and ast.SourceFile is ast.Program


def test_exception_types_number_like_the_paper():
    assert [t.number for t in ast.ExceptionType] == [1, 2, 3]
    assert ast.ExceptionType("abort") is ast.ExceptionType.ABORT


def test_signal_decl_valued():
    assert ast.SignalDecl(name="B", direction=ast.Direction.INPUT, type="float").valued
    assert not ast.SignalDecl(name="A", direction=ast.Direction.OUTPUT).valued


def test_protocol_table():
    assert len(ast.PROTOCOLS) == 8 and ast.DEFAULT_PROTOCOL in ast.PROTOCOLS
    assert ast.VALUE_TYPES >= {"float", "string", "vector", "duration"}


def test_every_statement_class_is_in_stmt_union():
    names = {c.__name__ for c in ast.Stmt.__args__}
    assert names >= {"Nothing", "Pause", "Halt", "Emit", "Sustain", "Await", "Run", "If",
                     "Loop", "Repeat", "Every", "Abort", "Suspend", "Trap", "Exit", "Try",
                     "Par", "Race", "LocalSignals", "VarDecl", "Assign", "Block"}


def test_ast_module_does_not_import_lark():
    import subprocess
    import sys
    code = "import sys, orccad_app.lang.ast; print('lark' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.stdout.strip() == "False", out.stderr
