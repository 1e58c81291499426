"""Make docs/sil-tracking.png: the tracking error of one mission run three ways, side by side.

``missions/arm_recovery.orc`` with ``--inject TrackPID.TrackingLost@2.5`` (a lost track at
2.5 s, the recovery through ``Home`` and a second ``TrackPID``), run by the simulated executive
(``orccad run``), by lockstep SIL (``orccad sil --lockstep``: the C Module-Tasks in their own
process) and by real-time SIL (``orccad sil --realtime``: on the runtime's threads, the plant
on the wall clock). Plots the largest ``|e|`` over the joints of the task error the control
laws wrote [rad]. Needs matplotlib (``pip install -e .[docs]``)::

    .venv/bin/python docs/make_sil_figure.py [OUT.png]
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
MISSION = ROOT / "missions" / "arm_recovery.orc"
INJECTION = "TrackPID.TrackingLost@2.5"


def _plan():
    from orccad_app.mission.plan import plan_mission
    from orccad_app.pipeline import load, select_mission

    source = load(str(MISSION))
    return plan_mission(source, select_mission(source, None))


def _options(plan) -> dict:
    from orccad_app.executive import Bus
    from orccad_app.executive.processor import Processor
    from orccad_app.mission.injection import parse_injection

    return {"until_ns": int(plan.run_horizon_s(60.0) * 1e9), "bus": Bus(),
            "processors": [Processor(name) for name in plan.processor_names],
            "injections": [parse_injection(INJECTION)]}


class _Errors:
    """The task errors the control laws write (an executive observer)."""

    def __init__(self) -> None:
        self.samples: list[tuple[float, float]] = []

    def wants_write(self, module: str, port: str) -> bool:
        return port == "e"

    def on_write(self, t_ns: int, module: str, port: str, value) -> None:
        if port == "e":
            self.samples.append((t_ns / 1e9, float(np.max(np.abs(value)))))


def executive() -> np.ndarray:
    from orccad_app.mission.run import MissionRun

    plan = _plan()
    seen = _Errors()
    MissionRun(plan, observers=[seen], **_options(plan)).run()
    return np.array(seen.samples)


def lockstep() -> np.ndarray:
    from orccad_app.mission.run import MissionRun
    from orccad_app.sil.lockstep import lockstep as in_lockstep

    plan = _plan()
    seen = _Errors()
    with in_lockstep(plan, str(MISSION)):
        MissionRun(plan, observers=[seen], **_options(plan)).run()
    return np.array(seen.samples)


def realtime() -> np.ndarray:
    from orccad_app.sil.realtime.run import RealtimeRun, realtime as in_realtime

    samples: list[tuple[float, float]] = []

    class Recorded(RealtimeRun):
        def task_error(self, module, value):
            samples.append((self.kernel.now / 1e9, float(np.max(np.abs(value)))))
            super().task_error(module, value)

    plan = _plan()
    with in_realtime(plan, str(MISSION)) as (table, controller, shared):
        Recorded(plan, table, controller, shared, **_options(plan)).run()
    return np.array(samples)


def main(out: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    runs = [("orccad run (simulated executive)", executive()),
            ("orccad sil --lockstep (C, own process)", lockstep()),
            ("orccad sil --realtime (threads, wall clock)", realtime())]
    figure, axes = plt.subplots(1, 3, figsize=(13, 3.6), sharey=True)
    for axis, (title, data) in zip(axes, runs):
        axis.plot(data[:, 0], data[:, 1] * 1e3, linewidth=0.8)
        axis.axvline(2.5, color="grey", linestyle=":", linewidth=0.8)
        axis.set_title(title, fontsize=10)
        axis.set_xlabel("time [s]")
        axis.grid(alpha=0.3)
    axes[0].set_ylabel("max |e| over the joints [mrad]")
    figure.suptitle("missions/arm_recovery.orc, TrackPID.TrackingLost injected at 2.5 s",
                    fontsize=11)
    figure.tight_layout()
    figure.savefig(out, dpi=110)
    print(f"wrote {out}")


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "docs" / "sil-tracking.png")
