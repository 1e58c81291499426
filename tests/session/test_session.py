"""The run façade: one way to run a mission, its report, its scoped signal handling."""

from __future__ import annotations

import json
import signal

import pytest

from orccad_app.cli import main
from orccad_app.diagnostics import OrccadError
from orccad_app.mission.injection import Injection, PlantFault, parse_injection
from orccad_app.pipeline import load, select_mission
from orccad_app.session import InputScript, RunOptions, RunSession, run_mission

PID = "missions/arm_pid.orc"
RECOVERY = "missions/arm_recovery.orc"


@pytest.fixture(scope="module")
def recovery():
    source = load(RECOVERY)
    return source, select_mission(source, None)


def test_the_signal_handlers_of_a_run_are_restored_after_it(recovery):
    before = {sent: signal.getsignal(sent) for sent in (signal.SIGINT, signal.SIGTERM)}
    seen = {}

    class Watch:
        def on_reaction(self, t_ns, inputs, outputs, status):
            seen.setdefault("during", signal.getsignal(signal.SIGTERM))

    run_mission(*recovery, RunOptions(until_s=0.01, signals_end_run=True, observers=(Watch(),)))
    assert seen["during"] not in (before[signal.SIGTERM], None)  # the run's own handler
    assert {sent: signal.getsignal(sent) for sent in before} == before


def test_orccad_run_in_process_leaves_no_signal_handler_behind(capsys):
    before = signal.getsignal(signal.SIGTERM)
    assert main(["run", PID, "--until", "0.05", "--json"]) == 1  # still running: timeout
    assert json.loads(capsys.readouterr().out)["status"] == "timeout"
    assert signal.getsignal(signal.SIGTERM) is before


def test_the_report_holds_the_injections_the_result_and_the_verdicts(recovery):
    options = RunOptions(injections=(parse_injection("Stop@0.2"), Injection("Gripper", 0, 1)),
                         until_s=1.0)
    report = run_mission(*recovery, options)
    assert [(i.name, i.time_ns, i.value) for i in report.injections] == [
        ("Gripper", 0, 1.0), ("Stop", 200_000_000, None)]
    assert type(report.injections[0].value) is float  # typed once, against the plan
    data = report.as_dict()
    assert [p["name"] for p in data["properties"]] == [p.name for p in report.properties]
    assert data["status"] == report.result.status
    assert report.text().startswith(f"mission ArmRecovery: {report.result.status}")
    assert report.exit_status == max(report.result.exit_status, 1 if report.violated else 0)


@pytest.mark.parametrize("injection, message", [
    (Injection("Stop", 0, 3), "Stop is a pure input"),
    (Injection("Gripper", 0, "x"), "is not a float value for Gripper"),
    (Injection("Nope", 0), "not an input of mission 'ArmRecovery'"),
    (Injection("Stop", 9_000_000_000), "after --until"),
    (Injection("arm.leak", 0, float("nan"), fault=PlantFault("arm", "leak")), "finite number"),
])
def test_bad_injections_are_refused_before_the_run(recovery, injection, message):
    with pytest.raises(OrccadError, match=message):
        RunSession(*recovery, RunOptions(injections=(injection,), until_s=2.0))


def test_an_input_script_is_read_against_the_plan_and_reported_by_its_file(recovery, tmp_path):
    script = tmp_path / "stop.in"
    script.write_text("Stop\n")
    session = RunSession(*recovery, RunOptions(script=InputScript.from_file(str(script)),
                                               until_s=1.0))
    assert [(r.name, r.time_ns, r.by) for r in session.injected] == [
        ("Stop", 0, f"--inject-from {script}")]
    bad = tmp_path / "bad.in"
    bad.write_text("Nope\n")
    with pytest.raises(OrccadError, match="Nope"):
        RunSession(*recovery, RunOptions(script=InputScript.from_file(str(bad))))


def test_the_horizon_defaults_to_the_robot_types_and_is_capped_at_a_year(recovery):
    assert RunSession(*recovery).until_ns == 60_000_000_000
    with pytest.raises(OrccadError, match=r"3\.1536e\+07 s simulated"):  # a year: over budget
        RunSession(*recovery, RunOptions(until_s=1e12))
