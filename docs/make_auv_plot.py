"""Make docs/auv_depth_heading.png: depth and heading of missions/auv_survey.orc from traces.

Runs the mission three times in the executive (nominal, a leak at 100 s, a low battery at
100 s), each with a CSV trace, and plots what the autopilot read (``depth``, ``attitude``)
against its setpoint. Needs matplotlib (``pip install -e .[docs]``)::

    .venv/bin/python docs/make_auv_plot.py [OUT.png]
"""

from __future__ import annotations

import csv
import json
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
MISSION = ROOT / "missions" / "auv_survey.orc"
RUNS = (("nominal (done)", ()), ("leak at 100 s (aborted)", ("auv.leak=1@100",)),
        ("battery 15 % at 100 s (failed)", ("auv.battery=15%@100",)))


def run_with_trace(injections: tuple[str, ...], path: Path):
    """Run the mission with a CSV trace at ``path``; return the run result."""
    from orccad_app.mission.plan import plan_mission
    from orccad_app.mission.injection import parse_injection
    from orccad_app.mission.run import MissionRun
    from orccad_app.pipeline import load, select_mission
    from orccad_app.trace import TraceRecorder, open_trace

    source = load(str(MISSION))
    plan = plan_mission(source, select_mission(source, None))
    run = MissionRun(plan, until_ns=900_000_000_000,
                     injections=[parse_injection(text) for text in injections])
    writer = open_trace(str(path), {"mission": plan.name})
    run.add_observer(TraceRecorder(writer))
    try:
        return run.run()
    finally:
        writer.close()


def series(path: Path) -> dict[str, list[tuple[float, object]]]:
    """``port -> [(t_s, value)]`` of the autopilots' reads (depth, attitude, setpoint)."""
    out: dict[str, list] = {"depth": [], "attitude": [], "setpoint": []}
    with open(path, newline="") as stream:
        for row in csv.DictReader(stream):
            if row["event"] == "read" and row["module"].endswith(".pilot") \
                    and row["port"] in out and row["value"]:
                out[row["port"]].append((int(row["time_ns"]) / 1e9, json.loads(row["value"])))
    return out


def plot(out: Path) -> None:
    import matplotlib
    import numpy as np

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax_depth, ax_heading) = plt.subplots(2, 1, figsize=(9, 6.5), sharex=True)
    with tempfile.TemporaryDirectory() as tmp:
        for index, (label, injections) in enumerate(RUNS):
            trace = Path(tmp) / f"run{index}.csv"
            result = run_with_trace(injections, trace)
            data = series(trace)
            t, depth = zip(*data["depth"])
            ax_depth.plot(t, depth, ("-", "--", ":")[index], lw=1.4,
                          label=f"{label}, {result.sim_time_ns / 1e9:.0f} s")
            if index == 0:
                t_sp, sp = zip(*data["setpoint"])
                ax_depth.plot(t_sp, [s[0] for s in sp], "k--", lw=0.8, label="depth setpoint")
                t_att, att = zip(*data["attitude"])
                heading = np.degrees(np.unwrap([a[2] for a in att]))
                ax_heading.plot(t_att, heading, label="heading")
                ax_heading.plot(t_sp, np.degrees(np.unwrap([s[1] for s in sp])), "k--", lw=0.8,
                                label="heading setpoint (LOS)")
                for record in result.robot_tasks:
                    ax_heading.axvline(record.start_ns / 1e9, color="0.8", lw=0.6)
                    ax_heading.text(record.start_ns / 1e9 + 1, -80, record.name,
                                    rotation=90, fontsize=7, va="bottom")
    ax_depth.axhline(30.0, color="r", lw=0.8, ls=":", label="depth limit 30 m")
    ax_depth.invert_yaxis()
    ax_depth.set_ylabel("depth [m]")
    ax_depth.legend(fontsize=7, loc="lower right")
    ax_depth.set_title("missions/auv_survey.orc in the executive (MuJoCo plant)")
    ax_heading.set_ylabel("heading [deg]")
    ax_heading.set_xlabel("time [s]")
    ax_heading.set_ylim(-90, 270)
    ax_heading.legend(fontsize=7, loc="upper right")
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print(f"wrote {out}")


if __name__ == "__main__":
    plot(Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "docs" / "auv_depth_heading.png")
