"""missions/arm_recovery.orc parks the arm on Stop and finishes only then (issue 18, defect 2).

Before, a race branch ended 0.5 s after Stop and killed the park: ``orccad run
missions/arm_recovery.orc --inject Stop@3`` gave ``Home 3.000 → 3.501 s killed`` and the
mission still said ``done``. The mission's properties ``park_completes`` and
``parked_before_done`` state the intent; ``orccad check`` proves them, and refutes them on the
old race.
"""

from __future__ import annotations

import shutil
import json
import subprocess
import sys
from pathlib import Path

MISSION = Path("missions/arm_recovery.orc")
OLD_BRANCH_END = "            halt;                                      // the park ends the race, not this\n"


def cli(*args):
    return subprocess.run([sys.executable, "-m", "orccad_app.cli", *args],
                          capture_output=True, text=True)


def test_stop_during_tracking_parks_the_arm_to_its_end():
    result = cli("run", str(MISSION), "--inject", "Stop@3", "--json")
    assert result.returncode == 0, result.stderr
    report = json.loads(result.stdout)
    assert report["status"] == "done"
    tasks = [(t["name"], t["outcome"]) for t in report["robot_tasks"]]
    assert tasks == [("Home", "good_end"), ("TrackPID", "killed"), ("Park", "good_end")]
    park = report["robot_tasks"][-1]
    assert park["start_s"] == 3.0 and park["end_s"] >= 4.9  # its 2 s duration, not 0.5 s
    assert report["sim_time_s"] >= park["end_s"]


def test_check_proves_the_park_properties():
    result = cli("check", str(MISSION))
    assert result.returncode == 0, result.stdout + result.stderr
    assert "ok    property park_completes" in result.stdout
    assert "ok    property parked_before_done" in result.stdout


def test_the_properties_catch_a_race_that_ends_during_the_park(tmp_path):
    text = MISSION.read_text(encoding="utf-8")
    assert OLD_BRANCH_END in text
    shutil.copytree(MISSION.parent / "lib", tmp_path / "lib")  # the sub-missions it imports
    buggy = tmp_path / "buggy.orc"
    buggy.write_text(text.replace(OLD_BRANCH_END, ""), encoding="utf-8")
    result = cli("check", str(buggy))
    assert result.returncode == 1
    assert "FAIL  property park_completes" in result.stdout
    assert "FAIL  property parked_before_done" in result.stdout
    # the counterexample says the park is the sub-mission Parking, run by the 'do' of Stop
    call = next(n for n, line in enumerate(text.splitlines(), 1) if "run mission Parking" in line)
    assert f"# in Parking#1 ({tmp_path / 'lib' / 'parking.orc'}:8) inside {buggy}:{call}" \
        in result.stdout
