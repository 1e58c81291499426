"""Helpers: compile a mission from source and run it instant by instant."""

from __future__ import annotations

import pytest

from orccad_app.lang.parser import parse
from orccad_app.reactive.compiler import compile_program
from orccad_app.reactive.lower import lower_mission
from orccad_app.reactive.runtime import Reactor
from orccad_app.reactive.script import parse_script


def compile_source(source: str, mission: str | None = None, **options):
    program = parse(source, "test.orc")
    chosen = program.mission(mission) if mission else program.missions[0]
    return compile_program(lower_mission(program, chosen), **options)


def mission(decls: str, body: str) -> str:
    return f"mission M {{\n{decls}\n{body}\n}}\n"


class Run:
    """The outputs of each instant as text (``O``, ``V(3)``, ``-`` for none), and statuses."""

    def __init__(self, source: str, script: list[str], mission_name: str | None = None):
        self.automaton = compile_source(source, mission_name)
        reactor = Reactor(self.automaton)
        instants = parse_script("\n".join(script) + "\n", "script.in", self.automaton.inputs)
        assert len(instants) == len(script)
        self.outputs: list[str] = []
        self.statuses: list[str] = []
        for instant in instants:
            reaction = reactor.react(instant.inputs, instant.time_ns)
            text = " ".join(f"{o}({reaction.values[o]})" if o in reaction.values else o
                            for o in reaction.outputs)
            self.outputs.append(text or "-")
            self.statuses.append(reaction.status)
        self.reactor = reactor


@pytest.fixture
def run():
    return Run
