"""The run report tells the story first (issue 18, defect 3): Robot-Tasks, exceptions, what was
injected and the outputs — a sustained output as one line ``Beat ×N, first–last s``, so it
no longer hides ``Finished`` — then the Module-Task table."""

from __future__ import annotations

import json
import subprocess
import sys


def cli(*args):
    return subprocess.run([sys.executable, "-m", "orccad_app.cli", *args],
                          capture_output=True, text=True)


ARGS = ("run", "missions/arm_recovery.orc", "--inject", "Stop@3", "--inject", "Gripper(0.8)@2",
        "--inject", "Gripper(0.2)@2.5")


def test_text_report_groups_outputs_lists_injections_and_puts_the_story_first():
    result = cli(*ARGS)
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert lines[0] == "mission ArmRecovery: done"
    order = [lines.index(head) for head in
             ("Robot-Tasks:", "Injections:", "Outputs:", "Module-Tasks (times in ms):")]
    assert order == sorted(order)
    injections = lines[lines.index("Injections:") + 1:lines.index("Outputs:")]
    assert injections == ["  2.000 s  Gripper(0.8) (input, --inject)",
                          "  2.500 s  Gripper(0.2) (input, --inject)",
                          "  3.000 s  Stop (input, --inject)"]
    outputs = lines[lines.index("Outputs:") + 1:lines.index("Module-Tasks (times in ms):")]
    assert outputs == ["  Started 0.000 s", "  Beat ×3501, 1.500–5.000 s", "  Grip(0.8) 2.000 s",
                       "  Stopping 3.500 s", "  Finished 5.000 s"]


def test_json_report_lists_injections_with_their_kind():
    result = cli(*ARGS, "--json")
    report = json.loads(result.stdout)
    assert report["injections"][-1] == {"time_s": 3.0, "name": "Stop", "value": None,
                                        "kind": "input", "by": "--inject", "applied": True}
    assert report["injections"][0]["value"] == 0.8
    beats = [o for o in report["outputs"] if o["name"] == "Beat"]  # grouped as in the text
    assert beats == [{"time_s": 1.5001, "until_s": 5.0, "name": "Beat", "count": 3501,
                      "values": None}]
    assert [o["name"] for o in report["outputs"]] == ["Started", "Beat", "Grip", "Stopping",
                                                      "Finished"]
    assert report["outputs"][2] == {"time_s": 2.0, "name": "Grip", "value": 0.8}


def test_a_plant_fault_is_listed_as_such():
    result = cli("run", "missions/auv_survey.orc", "--inject", "auv.leak=1@20", "--until", "40")
    assert result.returncode == 1
    assert "  20.000 s  auv.leak = 1 (plant fault, --inject)" in result.stdout.splitlines()
