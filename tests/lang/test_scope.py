"""Scopes, the error collector and classify_condition."""

from __future__ import annotations

import pytest

from orccad_app.diagnostics import OrccadError, SourceLocation
from orccad_app.lang import ast
from orccad_app.lang.scope import (Binding, ConditionKind, NameKind, Problems, Scope,
                                   classify_condition, signal_leaves)

S, T, X = (ast.Name(name=n) for n in "STx")
KINDS = {"S": NameKind.SIGNAL, "T": NameKind.SIGNAL, "x": NameKind.VARIABLE}


def binary(op, left, right):
    return ast.Binary(op=op, left=left, right=right)


def test_inner_scope_sees_outer_names_and_shadows_them():
    outer = Scope()
    outer.names["S"] = Binding(NameKind.SIGNAL, ast.SignalDecl(name="S",
                                                               direction=ast.Direction.INPUT))
    inner = outer.child()
    inner.names["x"] = Binding(NameKind.VARIABLE, ast.VarDecl(name="x", value=ast.Number(
        value=1)))
    assert inner.lookup("S").kind is NameKind.SIGNAL and outer.lookup("x") is None
    assert inner.kinds() == {"S": NameKind.SIGNAL, "x": NameKind.VARIABLE}
    assert inner.lookup("x").valued and not inner.lookup("S").valued


@pytest.mark.parametrize("condition", [
    S, ast.Unary(op="not", operand=S), binary("and", S, ast.Unary(op="not", operand=T)),
    binary("or", binary("and", S, T), T)])
def test_presence_conditions(condition):
    assert classify_condition(condition, KINDS) is ConditionKind.SIGNAL


@pytest.mark.parametrize("condition", [
    X, binary(">", X, ast.Number(value=2)), ast.LastValue(signal="S"),
    binary("and", X, ast.Bool(value=True)), ast.Unary(op="not", operand=X)])
def test_data_conditions(condition):
    assert classify_condition(condition, KINDS) is ConditionKind.DATA


def test_mixed_and_buried_signals_are_errors():
    with pytest.raises(OrccadError, match="mixes the presence of signal 'S'"):
        classify_condition(binary("and", S, X), KINDS)
    with pytest.raises(OrccadError, match="signal 'S' used as a value"):
        classify_condition(binary(">", binary("+", S, X), X), KINDS)


def test_classify_accepts_a_scope():
    scope = Scope()
    scope.names["S"] = Binding(NameKind.SIGNAL, ast.SignalDecl(name="S",
                                                               direction=ast.Direction.LOCAL))
    assert classify_condition(S, scope) is ConditionKind.SIGNAL


def test_signal_leaves():
    assert signal_leaves(binary("or", S, ast.Unary(op="not", operand=T))) == (S, T)
    assert signal_leaves(binary(">", X, X)) == (binary(">", X, X),)


def test_problems_raise_the_first_with_the_rest_as_notes():
    problems = Problems()
    problems.raise_if_any()  # nothing collected: no error
    here, there = SourceLocation("f", 2, 3), SourceLocation("f", 1, 1)
    problems.error("first", here, previous=there)
    problems.error("second", there)
    with pytest.raises(OrccadError) as caught:
        problems.raise_if_any()
    error = caught.value
    assert (error.message, error.location) == ("first", here)
    assert [(n.severity, n.message) for n in error.notes] == [
        ("note", "previous declaration here"), ("error", "second")]
