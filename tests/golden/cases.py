"""The golden cases: every shipped mission, compiled and run at a fixed seed.

Each case is one ``orccad`` command line; its outputs (stdout, and the CSV trace when the case
writes one) are stored under ``tests/golden/data/``. ``wall_time_s`` is the only field of a run
report that depends on the machine; it is replaced by ``0.0`` before comparison.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
DATA = Path(__file__).resolve().parent / "data"
MISSIONS = ROOT / "missions"


@dataclass(frozen=True)
class Case:
    """One golden command.

    :param name: file stem of its references in ``data/``.
    :param argv: the ``orccad`` arguments (mission paths relative to the repository root).
    :param trace: whether the case writes a CSV trace (stored gzip-compressed).
    """

    name: str
    argv: tuple[str, ...]
    trace: bool = False


def _compile(stem: str, mission: str, name: str | None = None) -> Case:
    return Case(f"compile-{name or stem}",
                ("compile", f"missions/{stem}.orc", "-m", mission, "--format", "json"))


def _run(name: str, stem: str, *args: str, trace: bool = False) -> Case:
    return Case(f"run-{name}", ("run", f"missions/{stem}.orc", "--seed", "0", "--json", *args),
                trace=trace)


CASES: tuple[Case, ...] = (
    _compile("abro", "ABRO"),
    _compile("arm_computed_torque", "ArmComputedTorque"),
    _compile("arm_pid", "ArmPID"),
    _compile("arm_recovery", "ArmRecovery"),
    _compile("auv_survey", "AuvSurvey"),
    _compile("false_property", "PickPlace"),
    _compile("arm_computed_torque_multirate", "ArmComputedTorqueMultirate"),
    _compile("arm_interrupts", "ArmInterrupts"),
    _compile("arm_interrupts", "ArmInterruptsTight", "arm_interrupts-tight"),
    _compile("arm_retune", "ArmRetune"),
    _compile("auv_waypoints", "AuvWaypoints"),
    # full runs: the report covers the whole mission
    _run("arm_computed_torque", "arm_computed_torque"),
    _run("arm_pid", "arm_pid"),
    _run("arm_recovery", "arm_recovery"),
    _run("arm_recovery-lost", "arm_recovery", "--inject", "TrackPID.TrackingLost@3"),
    _run("auv_survey", "auv_survey"),
    _run("auv_survey-leak", "auv_survey", "--inject", "auv.leak=1@100"),
    _run("false_property", "false_property"),
    _run("arm_computed_torque_multirate", "arm_computed_torque_multirate"),
    _run("arm_interrupts", "arm_interrupts", "-m", "ArmInterrupts"),
    _run("arm_interrupts-tight", "arm_interrupts", "-m", "ArmInterruptsTight"),
    _run("arm_retune", "arm_retune"),
    _run("auv_waypoints", "auv_waypoints", "--until", "60", "--inject", "Waypoint([15, 0, 5])@1"),
    # traces: short horizons keep the references small (each crosses a Robot-Task boundary
    # where the mission has one)
    _run("arm_pid-trace", "arm_pid", "--until", "0.3", trace=True),
    _run("arm_computed_torque-trace", "arm_computed_torque", "--until", "0.3", trace=True),
    _run("arm_recovery-trace", "arm_recovery", "--until", "1.6", trace=True),
    _run("auv_survey-trace", "auv_survey", "--until", "12", trace=True),
    _run("false_property-trace", "false_property", "--until", "2", trace=True),
    _run("arm_computed_torque_multirate-trace", "arm_computed_torque_multirate", "--until", "0.3",
         trace=True),
    _run("arm_interrupts-trace", "arm_interrupts", "-m", "ArmInterrupts", "--until", "0.3",
         trace=True),
    _run("arm_retune-trace", "arm_retune", "--until", "0.5", trace=True),
    _run("auv_waypoints-trace", "auv_waypoints", "--until", "10", "--inject",
         "Waypoint([15, 0, 5])@1", trace=True),
    # a run-time argument refused when its task starts: failed at the argument
    _run("auv_waypoints-refused", "auv_waypoints", "--inject", "Waypoint([15, 0, -5])@1"),
)
