"""Helpers: write a .orc file, compile a Robot-Task's RTA or a mission, run input scripts."""

from __future__ import annotations

from pathlib import Path

import pytest

from orccad_app.pipeline import ABSTRACT, COMPOSED, compile_mission, load, select_mission
from orccad_app.reactive.compiler import compile_program
from orccad_app.reactive.runtime import Reactor
from orccad_app.reactive.script import parse_script
from orccad_app.robottask.rta import rta_program

ARM_TASK = """
robot arm : arm3dof;
robottask {name}({params}) on arm {{
    {duration}
    task_function joint_tracking(trajectory = cosine(q0 = [0.5, 0.5, 0.5], omega = pi));
    law pid(kp = {kp}, kv = 40.0);
    module traj : trajectory  period 1 ms wcet 0.1 ms;
    module ctrl : control_law period 1 ms wcet 0.3 ms;
    connect traj.qd -> ctrl.qd;
    connect arm.q -> ctrl.q;
    connect arm.qdot -> ctrl.qdot;
    connect ctrl.tau -> arm.tau;
{clauses}
}}
"""


def arm_task(name: str = "T", clauses: str = "", duration: str = "duration 2 s;",
             params: str = "kp: float = 400.0", kp: str = "kp") -> str:
    return ARM_TASK.format(name=name, clauses=clauses, duration=duration, params=params, kp=kp)


class Trace:
    """Outputs (declaration order) and status of each instant of a script."""

    def __init__(self, automaton, script: list[str]):
        self.automaton = automaton
        self.reactor = Reactor(automaton)
        self.outputs: list[set[str]] = []
        self.statuses: list[str] = []
        for instant in parse_script("\n".join(script) + "\n", "script", automaton.inputs):
            reaction = self.reactor.react(instant.inputs, instant.time_ns)
            self.outputs.append(set(reaction.outputs))
            self.statuses.append(reaction.status)

    @property
    def reason(self) -> str | None:
        return self.reactor.reason


@pytest.fixture
def orc(tmp_path):
    def write(text: str):
        path = Path(tmp_path) / "t.orc"
        path.write_text(text, encoding="utf-8")
        return load(path)
    return write


def rta(source, task: str):
    return compile_program(rta_program(source.program.robottask(task)))


def mission_automaton(source, view: str = ABSTRACT, name: str | None = None):
    return compile_mission(source, select_mission(source, name), view=view)


__all__ = ["arm_task", "Trace", "rta", "mission_automaton", "ABSTRACT", "COMPOSED"]
