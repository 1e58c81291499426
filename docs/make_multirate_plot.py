"""Make docs/multirate-error.png: the split computed torque's tracking error against the model's
update period (missions/arm_computed_torque_multirate.orc, RR-1801 §6.2).

Runs the mission with the ``dynamic_model`` Module-Task at 1, 2, 5, 10 and 20 ms (execution
time ``min(2 ms, T/2)``, on cpu1 across a 50 µs bus, as ``bench/timing_table.py --multirate``
does), records the task error ``e`` the feedback writes, and plots the largest ``|e|`` over
the joints during the 4 s for three periods, and the max and RMS error against the period.
Needs matplotlib (``pip install -e .[docs]``)::

    .venv/bin/python docs/make_multirate_plot.py [OUT.png]
"""

from __future__ import annotations

import re
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
MISSION = ROOT / "missions" / "arm_computed_torque_multirate.orc"
PERIODS_MS = (1, 2, 5, 10, 20)


def errors(period_ms: float) -> tuple[np.ndarray, np.ndarray]:
    """Times [s] and task errors [rad] the feedback wrote, model at ``period_ms``."""
    from orccad_app.executive import Bus, Observer
    from orccad_app.mission.plan import plan_mission
    from orccad_app.mission.run import MissionRun
    from orccad_app.pipeline import load, select_mission

    class Errors(Observer):
        def __init__(self) -> None:
            self.t: list[float] = []
            self.e: list[np.ndarray] = []

        def on_write(self, t_ns, module, port, value):
            if module == "TrackCTMultirate.ctrl" and port == "e":
                self.t.append(t_ns / 1e9)
                self.e.append(np.asarray(value, dtype=float))

    text = re.sub(r"module model : dynamic_model\s+period 10 ms wcet 2 ms",
                  f"module model : dynamic_model period {period_ms:g} ms "
                  f"wcet {min(2.0, period_ms / 2):g} ms", MISSION.read_text(encoding="utf-8"))
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / MISSION.name
        path.write_text(text, encoding="utf-8")
        source = load(path)
        seen = Errors()
        MissionRun(plan_mission(source, select_mission(source, None)),
                   bus=Bus(transfer_ns=50_000), observers=[seen]).run()
    return np.array(seen.t), np.array(seen.e)


def main(out: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    runs = {period: errors(period) for period in PERIODS_MS}
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4), width_ratios=(2, 1))
    for period in (20, 5, 1):
        t, e = runs[period]
        left.plot(t, np.abs(e).max(axis=1) * 1e3, lw=0.8, label=f"model every {period} ms")
    left.set(xlabel="t [s]", ylabel="max over joints |e| [mrad]",
             title="feedback every 1 ms, model every T_model")
    left.legend()
    peak = [np.abs(runs[p][1]).max() * 1e3 for p in PERIODS_MS]
    rms = [np.sqrt(np.mean(runs[p][1] ** 2)) * 1e3 for p in PERIODS_MS]
    right.plot(PERIODS_MS, peak, "o-", label="max |e|")
    right.plot(PERIODS_MS, rms, "s-", label="RMS e")
    right.set(xlabel="model update period [ms]", ylabel="[mrad]", title="tracking error")
    right.legend()
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print(f"wrote {out}")


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "docs" / "multirate-error.png")
