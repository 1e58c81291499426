"""Issue 12: a fault's value range is declared by the plugin that offers the fault and checked
by ``--inject`` and the TUI alike (exit 2 with the fault and its range)."""

from __future__ import annotations

import math
import subprocess
import sys

import pytest

from orccad_app.control.plant_extension import FaultRange
from orccad_app.diagnostics import OrccadError
from orccad_auv.physics import AuvPhysics

AUV = "missions/auv_survey.orc"


@pytest.mark.parametrize("injection, words", [
    ("auv.depth_bias=nan@1", "finite"),
    ("auv.battery=200%@1", "[0, 100]"),
    ("auv.thrust=1e308@1", "[0, 1]"),
    ("auv.thrust=-1@1", "[0, 1]"),
    ("auv.leak=2@1", "0 or 1"),
])
def test_inject_refuses_a_value_out_of_the_faults_range(injection, words):
    done = subprocess.run([sys.executable, "-m", "orccad_app", "run", AUV, "--until", "2",
                           "--inject", injection], capture_output=True, text=True, timeout=300)
    assert done.returncode == 2, done.stderr
    assert words in done.stderr and "Traceback" not in done.stderr


def test_the_auv_declares_a_range_for_every_fault():
    physics = AuvPhysics.__new__(AuvPhysics)
    assert set(AuvPhysics.fault_ranges) == set(AuvPhysics.faults)
    assert physics.check_fault("battery", 5) == 5.0
    assert physics.check_fault("leak", True) == 1.0
    with pytest.raises(OrccadError, match="out of its range"):
        physics.check_fault("depth_bias", math.inf)


def test_a_fault_range_refuses_non_numbers_and_non_finite_values():
    with pytest.raises(OrccadError, match="expected a number"):
        FaultRange().check("x", "abc")
    with pytest.raises(OrccadError):
        FaultRange().check("x", math.nan)
    assert FaultRange(0, 1).check("x", 0.5) == 0.5


def test_the_tui_checks_a_fault_like_inject(plan_file_auv):
    observer = plan_file_auv
    with pytest.raises(OrccadError, match=r"\[0, 100\]"):
        observer.inject_fault("auv.battery", 200)
    observer.inject_fault("auv.battery", 50)  # accepted, queued


@pytest.fixture
def plan_file_auv():
    from orccad_app.mission.plan import plan_mission
    from orccad_app.mission.run import MissionRun
    from orccad_app.pipeline import load, select_mission
    from orccad_app.tui.live import LiveObserver
    from orccad_app.tui.pace import Pace

    source = load(AUV)
    run = MissionRun(plan_mission(source, select_mission(source, None)), until_ns=10**9)
    return LiveObserver(run, lambda update: None, Pace(None))
