"""A long run shows its progress on a terminal, and the progress line never changes the run."""

from __future__ import annotations

import io

from orccad_app.mission.plan import plan_mission
from orccad_app.mission.progress import ProgressLine
from orccad_app.mission.run import MissionRun
from orccad_app.pipeline import load, select_mission
from orccad_app.trace import report_dict


def _run(observers=()):
    source = load("missions/arm_pid.orc")
    plan = plan_mission(source, select_mission(source, None))
    mission_run = MissionRun(plan, seed=0, until_ns=300_000_000)
    for observer in observers:
        mission_run.add_observer(observer)
    return mission_run.run()


def test_the_progress_line_reports_simulated_time_against_the_horizon():
    stream = io.StringIO()
    progress = ProgressLine(stream, 300_000_000, delay_s=0.0, interval_s=0.0)
    _run([progress])
    text = stream.getvalue()
    assert "\r\033[K  simulated" in text and "of 0.3 s" in text and "real time" in text
    progress.close()
    assert stream.getvalue().endswith("\r\033[K")  # erased before the report


def test_a_watched_run_is_the_same_run():
    plain = _run()
    watched = _run([ProgressLine(io.StringIO(), 300_000_000, delay_s=0.0, interval_s=0.0)])
    reports = [report_dict(result, []) for result in (plain, watched)]
    for report in reports:
        report.pop("wall_time_s")
    assert reports[0] == reports[1]


def test_short_runs_print_nothing():
    stream = io.StringIO()
    _run([ProgressLine(stream, 300_000_000, delay_s=3600.0)])
    assert stream.getvalue() == ""
