"""Lockstep SIL ends as ``orccad run`` does on every shipped mission with a robot: same status,
Robot-Task runs (outcomes and times), exceptions, tracking errors, module statistics — bit for
bit, since the C Module-Tasks compute what the Python ones do and the timing model is the
same. A mission whose Module-Tasks have no C is refused with the kind and the reason."""

from __future__ import annotations

import subprocess
import sys

import pytest

from orccad_app.sil.layout import NoCImplementation
from orccad_app.sil.lockstep import lockstep

from tests.sil.helpers import MISSIONS, mission_run, plan_of, report

#: (file, mission) of every shipped mission that runs a robot and has C for all its kinds
RUNNABLE = [("arm_pid.orc", None), ("arm_recovery.orc", None), ("arm_retune.orc", None),
            ("arm_interrupts.orc", "ArmInterrupts"), ("arm_interrupts.orc", "ArmInterruptsTight"),
            ("auv_survey.orc", None), ("auv_waypoints.orc", None), ("false_property.orc", None)]
#: the shipped missions refused, with the reason's words
REFUSED = [("arm_computed_torque.orc", "computed_torque"),
           ("arm_computed_torque_multirate.orc", "ct_feedback")]


def test_every_shipped_mission_with_a_robot_is_listed():
    listed = {file for file, _ in RUNNABLE} | {file for file, _ in REFUSED}
    with_robot = {path.name for path in MISSIONS.glob("*.orc")
                  if "robot " in path.read_text() and "mission " in path.read_text()}
    assert with_robot == listed


@pytest.mark.parametrize("file,mission", RUNNABLE)
def test_lockstep_ends_as_the_executive(file, mission):
    expected = report(mission_run(plan_of(file, mission)).run())
    plan = plan_of(file, mission)
    with lockstep(plan, file) as controller:
        got = report(mission_run(plan).run())
        assert controller.alive
    assert not controller.alive
    assert got == expected


@pytest.mark.parametrize("file,kind", REFUSED)
def test_a_kind_without_c_is_refused_with_its_name_and_reason(file, kind):
    with pytest.raises(NoCImplementation, match=kind) as refused:
        with lockstep(plan_of(file), file):
            pass
    assert "no C implementation" in refused.value.message
    assert refused.value.location is not None


def test_the_command_exits_2_on_a_kind_without_c():
    done = subprocess.run([sys.executable, "-m", "orccad_app", "sil",
                           str(MISSIONS / "arm_computed_torque.orc"), "--lockstep"],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 2
    assert "computed_torque" in done.stderr and "Traceback" not in done.stderr


def test_an_injected_exception_reaches_the_controllers_run():
    """--inject: the tracking-loss exception of arm_pid ends the lockstep run as it ends the
    executive's (same outcome and instant)."""
    from orccad_app.mission.injection import parse_injection

    inject = [parse_injection("TrackPID.TrackingLost@1.0")]
    expected = report(mission_run(plan_of("arm_pid.orc"), injections=inject).run())
    plan = plan_of("arm_pid.orc")
    with lockstep(plan, "arm_pid.orc"):
        got = report(mission_run(plan, injections=inject).run())
    assert got["status"] == "failed" and got == expected
