"""Tracking error against the control period and execution time (RR-1801 §6.2), in the executive.

Runs missions/arm_computed_torque.orc and missions/arm_pid.orc (4 s of the paper's trajectory)
with the control law's period ``T`` and execution time ``C`` varied (the trajectory module
keeps the period, with zero execution time) and prints the RMS tracking error of each run as a
Markdown table for docs/control.md. A run whose mission fails (``TrackingLost``: the error
exceeded 0.2 rad) is marked so.

    python bench/timing_table.py [--periods 1 2 3 4] [--fractions 0 0.25 0.5 0.75]
"""

from __future__ import annotations

import argparse
import re
import tempfile
from pathlib import Path

from orccad_app.mission.plan import plan_mission
from orccad_app.mission.run import MissionRun
from orccad_app.pipeline import load, select_mission

ROOT = Path(__file__).resolve().parents[1]
MISSIONS = {"computed_torque": ROOT / "missions" / "arm_computed_torque.orc",
            "pid": ROOT / "missions" / "arm_pid.orc"}


def rms_error(path: Path, period_ms: float, wcet_ms: float) -> str:
    """The run's RMS error [rad] as text, or its failure."""
    text = path.read_text(encoding="utf-8")
    text = re.sub(r"(module traj : trajectory\s+)period 1 ms wcet [0-9.]+ ms",
                  rf"\g<1>period {period_ms:g} ms wcet 0 ms", text)
    text = re.sub(r"(module ctrl : control_law\s+)period 1 ms wcet [0-9.]+ ms",
                  rf"\g<1>period {period_ms:g} ms wcet {wcet_ms:g} ms", text)
    with tempfile.TemporaryDirectory() as folder:
        edited = Path(folder) / path.name
        edited.write_text(text, encoding="utf-8")
        source = load(edited)
        result = MissionRun(plan_mission(source, select_mission(source, None))).run()
    if result.status != "done":
        return f"{result.reason} at {result.sim_time_ns / 1e9:g} s"
    return f"{result.rms_error():.3e}"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--periods", type=float, nargs="+", default=[1, 2, 3, 4])
    parser.add_argument("--fractions", type=float, nargs="+", default=[0, 0.25, 0.5, 0.75])
    args = parser.parse_args()
    for law, path in MISSIONS.items():
        print(f"\n{law}: RMS tracking error [rad]\n")
        print("| T \\ C | " + " | ".join(f"{f:g} T" for f in args.fractions) + " |")
        print("|---|" + "---|" * len(args.fractions))
        for period in args.periods:
            cells = [rms_error(path, period, fraction * period) for fraction in args.fractions]
            print(f"| {period:g} ms | " + " | ".join(cells) + " |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
