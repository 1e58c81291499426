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


def _run(execution_name: str) -> np.ndarray:
    """The task errors of one run through the run façade, its Module-Tasks run as
    ``execution_name`` (``simulated``, ``lockstep`` or ``realtime``) says."""
    from orccad_app.mission.injection import parse_injection
    from orccad_app.pipeline import load, select_mission
    from orccad_app.session import ControllerOptions, Execution, RunOptions, RunSession

    source = load(str(MISSION))
    seen = _Errors()
    options = RunOptions(injections=(parse_injection(INJECTION),), observers=(seen,),
                         execution=Execution(execution_name),
                         controller=ControllerOptions(str(MISSION)))
    RunSession(source, select_mission(source, None), options).execute()
    return np.array(seen.samples)


class _Errors:
    """The task errors the control laws write (an executive observer)."""

    def __init__(self) -> None:
        self.samples: list[tuple[float, float]] = []

    def wants_write(self, module: str, port: str) -> bool:
        return port == "e"

    def on_write(self, t_ns: int, module: str, port: str, value) -> None:
        if port == "e":
            self.samples.append((t_ns / 1e9, float(np.max(np.abs(value)))))


def main(out: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    runs = [("orccad run (simulated executive)", _run("simulated")),
            ("orccad sil --lockstep (C, own process)", _run("lockstep")),
            ("orccad sil --realtime (threads, wall clock)", _run("realtime"))]
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
