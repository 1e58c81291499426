"""Issue 15, RTA labels: the terminated state is not labelled ``[done]`` after a failure; a
Cartesian task error is reported in metres, a joint-space one in radians."""

from __future__ import annotations

import subprocess
import sys

from orccad_app.mission.run import MissionRun


def _orccad(*args: str) -> str:
    done = subprocess.run([sys.executable, "-m", "orccad_app", *args], capture_output=True,
                          text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    return done.stdout


def test_the_terminated_state_of_an_rta_is_not_labelled_done():
    text = _orccad("rta", "missions/arm_pid.orc", "--task", "TrackPID")
    terminated = text.split("(terminated)")[1].splitlines()[1:]
    assert terminated and all("[done]" not in line for line in terminated), terminated
    assert "[failed]" in text and "[done]" in text  # the entering transitions keep theirs


CARTESIAN = """
    duration 0.2 s;
    task_function cartesian_tracking(trajectory = constant(value = [0.3, 0.0, 0.5]));
    law pid(kp = 400.0, kv = 40.0);
}
mission M { run Reach(); }
"""


def test_task_error_units_follow_the_task_function(plan_text, hold_task, pid_run):
    _, result = pid_run
    assert result.robot_tasks[0].as_dict()["tracking_error"]["unit"] == "rad"
    head = hold_task.split("robottask Hold")[0]
    plan = plan_text(head + "robottask Reach() on arm {" + CARTESIAN)
    [record] = MissionRun(plan).run().robot_tasks
    assert record.as_dict()["tracking_error"]["unit"] == "m"


def test_a_run_ends_with_a_typed_status(pid_run):
    from orccad_app.mission.result import MissionStatus

    _, result = pid_run
    assert result.status is MissionStatus.DONE and result.exit_status == 0
