"""Make docs/mcap-topics.png: what a Foxglove Plot panel shows of an ORCCAD MCAP trace.

Runs missions/arm_recovery.orc with ``Stop`` at 3 s and an MCAP trace, reads the trace back
with the ``mcap`` reader only (as Foxglove does: topics, JSON messages, their schemas) and
draws the series a designer would put in a Plot panel — ``/plant/arm/q.value[0]`` against
``/ports/<task>/traj/qd.value[0]``, the tracking error ``/ports/<task>/ctrl/e`` — with the
``/mission/active/<Task>`` spans and the ``/log`` entries as markers. Needs matplotlib
(``pip install -e .[docs]``)::

    .venv/bin/python docs/make_mcap_figure.py [OUT.png]
"""

from __future__ import annotations

import json
import subprocess
import sys
import tempfile
from collections import defaultdict
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def read_topics(path: Path) -> dict[str, list[tuple[float, dict]]]:
    """Every message of the trace by topic: ``(time [s], message)``."""
    from mcap.reader import make_reader

    topics: dict[str, list[tuple[float, dict]]] = defaultdict(list)
    with path.open("rb") as stream:
        for _, channel, message in make_reader(stream).iter_messages():
            topics[channel.topic].append((message.log_time / 1e9, json.loads(message.data)))
    return topics


def main(out: str = str(ROOT / "docs" / "mcap-topics.png")) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    with tempfile.TemporaryDirectory() as folder:
        trace = Path(folder) / "recovery.mcap"
        subprocess.run([sys.executable, "-m", "orccad_app.cli", "run",
                        str(ROOT / "missions" / "arm_recovery.orc"), "--inject", "Stop@3",
                        "--trace", str(trace)], check=True, capture_output=True)
        topics = read_topics(trace)
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(9, 5.5), sharex=True)
    q = topics["/plant/arm/q"]
    top.plot([t for t, _ in q], [m["value"][0] for _, m in q], label="/plant/arm/q.value[0]")
    for task in ("Home_0", "TrackPID", "Park"):
        qd = topics.get(f"/ports/{task}/traj/qd", [])
        top.plot([t for t, _ in qd], [m["value"][0] for _, m in qd], "--",
                 label=f"/ports/{task}/traj/qd.value[0]")
        e = topics.get(f"/ports/{task}/ctrl/e", [])
        bottom.plot([t for t, _ in e], [max(abs(v) for v in m["value"]) for _, m in e],
                    label=f"|/ports/{task}/ctrl/e|∞")
    colors = {"Home": "tab:green", "TrackPID": "tab:blue", "Park": "tab:orange"}
    for topic, messages in topics.items():
        if topic.startswith("/mission/active/"):
            task = topic.rsplit("/", 1)[1]
            starts = [t for t, m in messages if m["value"] == 1]
            ends = [t for t, m in messages if m["value"] == 0]
            for start, end in zip(starts, ends + [q[-1][0]] * len(starts)):
                for axis in (top, bottom):
                    axis.axvspan(start, end, color=colors.get(task, "grey"), alpha=0.08)
                top.text(start + 0.03, 0.9, task, fontsize=8, transform=top.get_xaxis_transform())
    for t, entry in topics["/log"]:
        if entry["message"].startswith(("input Stop", "exception")):
            for axis in (top, bottom):
                axis.axvline(t, color="red", linewidth=0.8)
            bottom.text(t + 0.03, 0.9, entry["message"], color="red", fontsize=8,
                        transform=bottom.get_xaxis_transform())
    top.set_ylabel("joint 0 [rad]")
    bottom.set_ylabel("tracking error [rad]")
    bottom.set_xlabel("simulated time [s] (log_time)")
    top.legend(fontsize=7, loc="lower left")
    bottom.legend(fontsize=7, loc="upper left")
    top.set_title("missions/arm_recovery.orc --inject Stop@3: MCAP topics as Foxglove plots them",
                  fontsize=10)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print(out)


if __name__ == "__main__":
    main(*sys.argv[1:])
