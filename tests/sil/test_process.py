"""A controller process that crashes, hangs or whose plant server dies: the run ends
``failed`` with the reason, the trace is complete, and no process is left behind (tested by
killing and stopping the real process)."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from mcap.reader import make_reader

from orccad_app.session import Execution

from tests.sil.helpers import MISSIONS, session_of


def _controllers_of(parent: int) -> list[int]:
    """The pids of the live controller processes whose parent is ``parent``."""
    found = []
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            stat = (entry / "stat").read_text()
        except OSError:
            continue
        name = stat[stat.index("(") + 1:stat.rindex(")")]
        fields = stat[stat.rindex(")") + 2:].split()
        if int(fields[1]) == parent and name.startswith("orccad_control") and fields[0] != "Z":
            found.append(int(entry.name))
    return found


def _gone(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return True
    return False


class _SignalAt:
    """Sends ``signum`` to the controller process ``pid`` (set once the session has started
    it) at the first release at or after ``at_ns``."""

    def __init__(self, signum: int, at_ns: int) -> None:
        self.signum, self.at_ns, self.sent = signum, at_ns, False
        self.pid = 0

    def on_release(self, now: int, name: str, index: int) -> None:
        if now >= self.at_ns and not self.sent:
            self.sent = True
            os.kill(self.pid, self.signum)


@pytest.mark.parametrize("signum,words", [(signal.SIGKILL, "crashed: killed by SIGKILL"),
                                          (signal.SIGSTOP, "hung: no answer")])
def test_a_crashed_or_hung_controller_fails_the_run_with_its_reason(tmp_path, signum, words):
    trace = tmp_path / "run.mcap"
    signal_at = _SignalAt(signum, 10**9)
    session = session_of("arm_pid.orc", execution=Execution.LOCKSTEP, heartbeat_s=0.5,
                         trace=str(trace), observers=(signal_at,))
    signal_at.pid = session.backend.controller.pid
    result = session.execute().result
    assert session.backend.controller.failure is not None  # killed at once, in the run
    assert _gone(signal_at.pid)  # and reaped
    assert result.status == "failed"
    assert words in result.reason
    assert 1.0 <= result.sim_time_ns / 1e9 < 1.01
    with open(trace, "rb") as stream:  # complete: the summary is there, every message reads
        messages = list(make_reader(stream).iter_messages())
    assert max(message.log_time for _, _, message in messages) >= 999_000_000  # up to 1 s
    assert _controllers_of(os.getpid()) == []


def _orccad(*args: str) -> subprocess.Popen:
    return subprocess.Popen([sys.executable, "-m", "orccad_app", "sil", *args],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def _wait_for_controller(parent: int, timeout_s: float = 60.0) -> int:
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        found = _controllers_of(parent)
        if found:
            return found[0]
        time.sleep(0.02)
    raise AssertionError("the controller process did not start")


def _wait_for_run(controller: int, timeout_s: float = 60.0) -> None:
    """Until the controller has read 64 KiB of requests: the run is going (a controller
    killed before it answered HELLO is a run that could not start, exit 2)."""
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        io = Path(f"/proc/{controller}/io").read_text()
        if int(io.split("rchar:")[1].split()[0]) >= 65536:
            return
        time.sleep(0.02)
    raise AssertionError("the controller process started no run")


def test_killing_the_controller_under_the_command_ends_it_failed_with_the_reason():
    command = _orccad(str(MISSIONS / "auv_survey.orc"), "--lockstep", "--json")
    controller = _wait_for_controller(command.pid)
    _wait_for_run(controller)
    os.kill(controller, signal.SIGKILL)
    out, err = command.communicate(timeout=120)
    assert command.returncode == 1, err
    report = json.loads(out)
    assert report["status"] == "failed"
    assert "killed by SIGKILL" in report["reason"]
    assert _gone(controller)


def test_killing_the_plant_server_ends_the_controller_too():
    command = _orccad(str(MISSIONS / "auv_survey.orc"), "--lockstep")
    controller = _wait_for_controller(command.pid)
    command.kill()  # SIGKILL: no clean-up code of the plant server runs
    command.communicate(timeout=60)
    deadline = time.monotonic() + 10.0
    while time.monotonic() < deadline and not _gone(controller):
        time.sleep(0.02)  # the controller reads end-of-file on its socket and exits
    assert _gone(controller) or Path(f"/proc/{controller}/stat").read_text().split()[2] == "Z"


def test_ctrl_c_ends_the_run_with_its_report_and_no_process_left():
    command = _orccad(str(MISSIONS / "auv_survey.orc"), "--lockstep")
    controller = _wait_for_controller(command.pid)
    _wait_for_run(controller)
    command.send_signal(signal.SIGINT)
    out, err = command.communicate(timeout=120)
    assert command.returncode == 130, err
    assert "mission AuvSurvey: aborted (interrupted (Ctrl-C))" in out and "interrupted" in err
    assert _gone(controller)


def _c_enum(name: str) -> dict[str, int]:
    """``enum NAME`` of orccad_wire.h: member -> value."""
    import re

    from orccad_app.sil.generate.library import C_DIR

    text = (C_DIR / "orccad_wire.h").read_text()
    body = re.search(r"enum " + name + r" \{(.*?)\};", text, re.S).group(1)
    return {m: int(v) for m, v in re.findall(r"^\s*(\w+) = (\d+)", body, re.M)}


def test_the_wire_vocabulary_is_typed_the_same_on_both_sides():
    """Operations and reply statuses are enums on both ends of the socket, member for member
    (orccad_wire.h's orc_op and orc_status; process.py's Op and Reply)."""
    from orccad_app.sil.controller.process import Op, Reply

    assert _c_enum("orc_op") == {f"OP_{op.name}": op.value for op in Op}
    assert _c_enum("orc_status") == {f"ORC_{reply.name}": reply.value for reply in Reply}


def test_a_refused_request_names_the_reason(tmp_path):
    from orccad_app.sil.controller.process import ControllerFailure, Op
    from orccad_app.sil.lockstep import lockstep

    from tests.sil.helpers import plan_of

    with lockstep(plan_of("arm_pid.orc"), "arm_pid.orc") as started:
        with pytest.raises(ControllerFailure) as refused:
            started.controller.request(Op.INIT, 99)
    assert str(refused.value).endswith("refused request INIT for Module-Task 99: no such "
                                       "Module-Task in its table")
