"""Generating a mission written in a test: its automaton (full, as ``orccad codegen``
compiles it), its C, and the comparison of the compiled C with ``Reactor.step``."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from orccad_app.codegen.generate import CProgram
from orccad_app.codegen.mission import generate_mission
from orccad_app.codegen.names import default_prefix
from orccad_app.pipeline import compose_mission, load
from tests.codegen.cbuild import STRICT, build, run_trace
from tests.codegen.differential import first_difference, python_records

__all__ = ["Made", "make", "agree"]


@dataclass(frozen=True)
class Made:
    automaton: object
    program: CProgram


def make(path: Path, prefix: str | None = None) -> Made:
    """The automaton and C of the (first) mission of the file ``path``, as ``orccad codegen``
    makes them (the prefix by default the mission's)."""
    source = load(path)
    mission = source.program.missions[0]
    composition = compose_mission(source, mission, defer_double_emissions=True)
    return Made(composition.automaton,
                generate_mission(composition, prefix or default_prefix(mission.name)))


def agree(made: Made, script: Path, flags: tuple[str, ...] = STRICT + ("-O0",)) -> list[dict]:
    """Build ``made``'s C with ``flags``, run ``script`` through it and through
    ``Reactor.step``: the records, asserted equal."""
    binary = build(made.program, flags)
    got, _status, stderr = run_trace(binary, script)
    expected = python_records(made.automaton, script.read_text(encoding="utf-8"), str(script))
    difference = first_difference(expected, got)
    assert difference is None, f"{difference}\n{stderr}"
    return got
