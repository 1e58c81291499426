"""Helpers: load a source text, build the model of a mission, check formulas on it."""

from __future__ import annotations

import functools
from pathlib import Path

from orccad_app.lang.names import check
from orccad_app.lang.parser import parse
from orccad_app.verify.checker import check_formula, check_mission
from orccad_app.robottask.composition import compose
from orccad_app.verify.formula import from_ast
from orccad_app.verify.model import build_model

ROOT = Path(__file__).resolve().parents[2]
CORPUS = Path(__file__).resolve().parent / "corpus"


@functools.cache
def _host():
    """The installed plugins, loaded once for these tests."""
    from orccad_app.plugin_host.host import PluginHost
    return PluginHost.load()


def program_of(text: str, filename: str = "test.orc"):
    """Parse and name-check ``text`` (Robot-Tasks are checked against the plugins)."""
    program = parse(text, filename)
    check(program)
    if program.robottasks:
        from orccad_app.robottask.model import check_tasks
        check_tasks(program, _host())
    return program


def model_of(text: str, mission: str | None = None):
    program = program_of(text)
    chosen = program.mission(mission) if mission else program.missions[0]
    return build_model(compose(program, chosen))


def formula(text: str, mission: str = "M"):
    """The core formula of ``text`` written in the plan language (atoms unchecked)."""
    program = parse(f"property {mission}.p: {text};", "formula.orc")
    return from_ast(program.properties[0].formula)


def holds(model, text: str, assumptions=()) -> bool:
    lasso, _ = check_formula(model, formula(text), [formula(a) for a in assumptions])
    return lasso is None


def report_of(text: str, mission: str | None = None):
    program = program_of(text)
    chosen = program.mission(mission) if mission else program.missions[0]
    return check_mission(program, chosen)
