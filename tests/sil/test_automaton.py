"""The mission's automaton reacts in the controller process: the C of ``orccad codegen``,
linked beside the Module-Tasks and stepped by the run (``OP_REACT``). Reaction by reaction, it
does what the Python reactor does on the same inputs (outputs, values, state, instant status,
mission status and reason); what the generator refuses is refused by ``orccad sil``, located."""

from __future__ import annotations

import subprocess
import sys
from typing import Any

import pytest

from orccad_app.mission.injection import parse_injection
from orccad_app.reactive.runtime import Reactor
from orccad_app.sil import lockstep as sil_lockstep
from orccad_app.sil.controller.automaton import ControllerAutomaton
from orccad_app.session import Execution

from tests.sil.helpers import executive_report, report, session_of


class _Twin(ControllerAutomaton):
    """The controller's automaton, with the Python reactor stepped beside it on the same
    inputs and compared after every reaction."""

    compared: list[tuple[int, tuple[str, ...]]] = []

    def __init__(self, controller: Any, program: Any, automaton: Any) -> None:
        super().__init__(controller, program, automaton)
        self._python = Reactor(automaton)

    def step(self, inputs: Any = frozenset(), clock_ns: int | None = None) -> Any:
        python = self._python
        expected = python.step(inputs, clock_ns)
        values = python.values(expected)
        got = super().step(inputs, clock_ns)
        where = f"reaction {self.instant} at {clock_ns} ns, inputs {sorted(inputs)}"
        assert got.outputs == expected.outputs, where
        assert got.values == values, where
        assert got.valued == tuple(decl.name for decl in expected.valued), where
        assert (got.target, got.status) == (expected.target, expected.status), where
        assert (self.state, self.status, self.reason) == (python.state, python.status,
                                                          python.reason), where
        _Twin.compared.append((clock_ns or 0, got.outputs))
        return got


@pytest.fixture
def twin(monkeypatch):
    _Twin.compared = []
    monkeypatch.setattr(sil_lockstep, "ControllerAutomaton", _Twin)
    return _Twin


@pytest.mark.parametrize("file,mission,inject,until_s", [
    ("arm_recovery.orc", None, "TrackPID.TrackingLost@2.5", None),
    ("arm_interrupts.orc", "ArmInterrupts", None, None),
    ("arm_interrupts.orc", "ArmInterruptsTight", None, None),
    ("arm_retune.orc", None, None, None),
    ("auv_waypoints.orc", None, "Waypoint([15, 0, 5])@0.5", 60.0),  # valued, run-time args
])
def test_the_c_automaton_reacts_as_the_python_reactor_reaction_by_reaction(twin, file, mission,
                                                                          inject, until_s):
    injections = (parse_injection(inject),) if inject else ()
    options = {"until_s": until_s} if until_s else {}
    session = session_of(file, mission, Execution.LOCKSTEP, injections=injections, **options)
    got = report(session.execute())
    assert isinstance(session.backend.automaton, _Twin)
    assert session.run.reactor is session.backend.automaton
    reactions = twin.compared
    assert len(reactions) > 50  # every tick and every event, not a handful
    assert sum(1 for _, outputs in reactions if outputs) >= 2  # starts, ends, exceptions
    assert got == executive_report(file, mission, injections=injections, **options)


def test_the_run_steps_the_controllers_automaton():
    """Every reaction of the run is one OP_REACT: the C automaton's count is the run's, and
    its state is the one the run reports."""
    seen: list[int] = []

    class Reactions:
        def on_reaction(self, t_ns, inputs, outputs, status):
            seen.append(t_ns)

    session = session_of("arm_pid.orc", None, Execution.LOCKSTEP, observers=(Reactions(),),
                         until_s=0.5)
    session.execute()
    automaton = session.backend.automaton
    assert isinstance(automaton, ControllerAutomaton)
    assert automaton.instant == len(seen) > 100
    assert session.run.reactor is automaton


ROBOT_MISSION = """robot arm : arm3dof;
robottask Hold() on arm {{
    duration 1 s;
    task_function joint_tracking(trajectory = constant(value = [0.5, 0.5, 0.5]));
    law pid(kp = 400.0, kv = 40.0);
    module traj : trajectory period 1 ms wcet 0.1 ms on cpu0 priority 2;
    module ctrl : control_law period 1 ms wcet 0.3 ms on cpu0 priority 1;
    connect traj.qd -> ctrl.qd;
    connect traj.qd_dot -> ctrl.qd_dot;
    connect arm.q -> ctrl.q;
    connect arm.qdot -> ctrl.qdot;
    connect ctrl.tau -> arm.tau;
}}
mission M {{
    output O : int;
    {body}
}}
"""


def test_an_automaton_the_generator_refuses_is_refused_located(tmp_path):
    body = "var x := 0; run Hold(); x := x + 0.5; emit O(x);"
    path = tmp_path / "hold.orc"
    path.write_text(ROBOT_MISSION.format(body=body))
    assert subprocess.run([sys.executable, "-m", "orccad_app", "run", str(path)],
                          capture_output=True, text=True, timeout=120).returncode in (0, 1)
    done = subprocess.run([sys.executable, "-m", "orccad_app", "sil", str(path), "--lockstep"],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 2, done.stderr
    text = ROBOT_MISSION.format(body=body)
    line = text[:text.index("x + 0.5")].count("\n") + 1
    assert f"hold.orc:{line}:" in done.stderr and "has no C" in done.stderr, done.stderr
    assert "Traceback" not in done.stderr
