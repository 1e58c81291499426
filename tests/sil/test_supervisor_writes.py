"""Everything in the controller (issue 35 item 1): every shipped mission with a robot, run by
``orccad sil --realtime --json``, reports ``controller.supervisor_writes: 0`` — the supervisor
keeps only the plant and the trace — with the Robot-Task runs and outcomes of ``orccad run``."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
MISSIONS = [("arm_pid.orc", None, ()), ("arm_recovery.orc", None,
                                        ("--inject", "TrackPID.TrackingLost@1.8")),
            ("arm_retune.orc", None, ()), ("arm_interrupts.orc", "ArmInterrupts", ()),
            ("arm_interrupts.orc", "ArmInterruptsTight", ()),
            ("arm_computed_torque.orc", None, ()), ("arm_computed_torque_multirate.orc", None, ()),
            ("auv_survey.orc", None, ()),
            ("auv_waypoints.orc", None, ("--inject", "Waypoint([15, 0, 5])@0.5")),
            ("false_property.orc", None, ())]
UNTIL_S = 2.5


def _json(*args: str) -> dict:
    done = subprocess.run([sys.executable, "-m", "orccad_app.cli", *args, "--json"], cwd=ROOT,
                          capture_output=True, text=True, timeout=600)
    assert "Traceback" not in done.stderr, done.stderr[-2000:]
    return json.loads(done.stdout)


@pytest.mark.parametrize("file, mission, extra", MISSIONS)
def test_the_supervisor_writes_no_parameter_word_in_real_time(file, mission, extra):
    args = [f"missions/{file}", *(("--mission", mission) if mission else ()), *extra,
            "--until", str(UNTIL_S)]
    real = _json("sil", *args, "--realtime")
    assert real["controller"]["supervisor_writes"] == 0
    simulated = _json("run", *args)
    assert [t["name"] for t in real["robot_tasks"]] == \
        [t["name"] for t in simulated["robot_tasks"]]
    settled = [(t["name"], t["outcome"]) for t in simulated["robot_tasks"]
               if t["end_s"] is not None and t["end_s"] < UNTIL_S - 0.3]
    assert [(t["name"], t["outcome"]) for t in real["robot_tasks"]][:len(settled)] == settled
