"""Make docs/foxglove-arm.png: what the shipped Foxglove layout shows of a trace of the arm.

Runs ``missions/arm_recovery.orc`` with its control module slowed to a 4 ms period (the
tracking then saturates the torque: the type-1 exception ``Saturated`` lowers ``kp`` from 600
to 200) and ``Stop`` at 4 s, with an MCAP trace; reads the trace back with the ``mcap`` reader
alone and draws the panels of docs/foxglove-layout.json from its topics:

- **3D**: the arm at a few instants, each body's geometry (``/scene``) placed by composing the
  frames of ``/tf`` from ``world`` — every cylinder drawn as its axis, every sphere as a dot;
- **set-point vs measure**: ``/plant/arm/q.value[0]`` against each task's
  ``/ports/<task>/traj/qd.value[0]``;
- **gains**: ``/params/TrackPID/ctrl/kp.value``;
- **verdicts**: ``/properties/<name>.value`` (1 true, 0 undecided, -1 false);
- **state**: ``/mission/phase/<Task>.value`` as the spans of each phase.

Needs matplotlib (``pip install -e .[docs]``)::

    .venv/bin/python docs/make_foxglove_figure.py [OUT.png]
"""

from __future__ import annotations

import json
import subprocess
import sys
import tempfile
from collections import defaultdict
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
RUN = ["missions/arm_recovery.orc", "--timing", "TrackPID.ctrl.period_ms=4", "--inject",
       "Stop@4"]
"""The run drawn (``orccad run`` arguments)."""
SNAPSHOTS_S = (0.0, 1.5, 2.5, 3.5, 4.0, 6.0)
"""The instants [s] the 3D panel shows."""


def read_topics(path: Path) -> dict[str, list[tuple[float, dict]]]:
    """Every message of the trace by topic: ``(time [s], message)``."""
    from mcap.reader import make_reader

    topics: dict[str, list[tuple[float, dict]]] = defaultdict(list)
    with path.open("rb") as stream:
        for _, channel, message in make_reader(stream).iter_messages():
            topics[channel.topic].append((message.log_time / 1e9, json.loads(message.data)))
    return topics


def _matrix(translation: dict, rotation: dict) -> np.ndarray:
    x, y, z, w = (rotation[k] for k in "xyzw")
    rotate = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                       [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                       [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])
    found = np.eye(4)
    found[:3, :3] = rotate
    found[:3, 3] = [translation[k] for k in "xyz"]
    return found


def world_poses(transforms: list[dict]) -> dict[str, np.ndarray]:
    """Every frame's pose in ``world`` (4×4), composing the parent-to-child transforms."""
    local = {t["child_frame_id"]: (t["parent_frame_id"], _matrix(t["translation"],
                                                                 t["rotation"]))
             for t in transforms}
    poses = {"world": np.eye(4)}

    def pose(frame: str) -> np.ndarray:
        if frame not in poses:
            parent, matrix = local[frame]
            poses[frame] = pose(parent) @ matrix
        return poses[frame]
    for frame in local:
        pose(frame)
    return poses


def _at(series: list[tuple[float, dict]], time_s: float) -> dict:
    """The last message at or before ``time_s``."""
    found = series[0][1]
    for t, message in series:
        if t > time_s:
            break
        found = message
    return found


def draw_arm(axis, scene: dict, transforms: dict, color) -> None:
    """The scene's cylinders (as their axes) and spheres (as dots) at the frames' poses."""
    poses = world_poses(transforms["transforms"])
    for entity in scene["entities"]:
        if entity["id"].endswith("floor"):
            continue
        frame = poses[entity["frame_id"]]
        for cylinder in entity["cylinders"]:
            centre = _matrix(cylinder["pose"]["position"], cylinder["pose"]["orientation"])
            half = cylinder["size"]["z"] / 2
            ends = [frame @ centre @ np.array([0.0, 0.0, s * half, 1.0]) for s in (-1, 1)]
            axis.plot(*zip(*[e[:3] for e in ends]), color=color, linewidth=3)


def main(out: str = str(ROOT / "docs" / "foxglove-arm.png")) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    with tempfile.TemporaryDirectory() as folder:
        trace = Path(folder) / "recovery.mcap"
        subprocess.run([sys.executable, "-m", "orccad_app.cli", "run", *RUN, "--trace",
                        str(trace)], check=True, capture_output=True, cwd=ROOT)
        topics = read_topics(trace)
    fig = plt.figure(figsize=(12, 7.5))
    grid = fig.add_gridspec(4, 2, width_ratios=(1, 1.3))
    arm = fig.add_subplot(grid[:, 0], projection="3d")
    scene = topics["/scene"][0][1]
    colors = plt.cm.viridis(np.linspace(0, 0.9, len(SNAPSHOTS_S)))
    for time_s, color in zip(SNAPSHOTS_S, colors):
        draw_arm(arm, scene, _at(topics["/tf"], time_s), color)
        arm.plot([], [], color=color, linewidth=3, label=f"t = {time_s:g} s")
    arm.set(xlim=(-0.5, 0.7), ylim=(-0.6, 0.6), zlim=(0, 1.2), xlabel="x [m]", ylabel="y [m]",
            zlabel="z [m]", title="3D: /scene on /tf (frame world)")
    arm.legend(loc="upper left", fontsize=8)
    joint = fig.add_subplot(grid[0, 1])
    q = topics["/plant/arm/q"]
    joint.plot([t for t, _ in q], [m["value"][0] for _, m in q], label="q1 measured")
    for task in ("Home_0", "TrackPID", "Park"):
        qd = topics.get(f"/ports/{task}/traj/qd", [])
        joint.plot([t for t, _ in qd], [m["value"][0] for _, m in qd], "--",
                   label=f"{task.split('_')[0]} set-point")
    joint.set(ylabel="[rad]", title="joint 1: set-point vs measure")
    joint.legend(fontsize=7, ncol=2)
    gains = fig.add_subplot(grid[1, 1], sharex=joint)
    kp = topics["/params/TrackPID/ctrl/kp"]
    end_s = max(t for t, _ in topics["/tf"])
    gains.step([t for t, _ in kp] + [end_s], [m["value"] for _, m in kp] + [kp[-1][1]["value"]],
               where="post")
    gains.set(ylabel="kp", title="/params/TrackPID/ctrl/kp (type-1 update Saturated)")
    verdicts = fig.add_subplot(grid[2, 1], sharex=joint)
    for topic, series in sorted(topics.items()):
        if topic.startswith("/properties/"):
            verdicts.step([t for t, _ in series], [m["value"] for _, m in series], where="post",
                          label=topic.removeprefix("/properties/"))
    verdicts.set(ylim=(-1.2, 1.2), yticks=(-1, 0, 1),
                 yticklabels=("false", "undecided", "true"), title="/properties/<name>")
    verdicts.legend(fontsize=6, ncol=2, loc="lower right")
    state = fig.add_subplot(grid[3, 1], sharex=joint)
    phases = {1: "tab:gray", 2: "tab:orange", 3: "tab:green"}
    tasks = ("Home", "TrackPID", "Park")
    for row, task in enumerate(tasks):
        series = topics.get(f"/mission/phase/{task}", [])
        for (start, message), (end, _) in zip(series, series[1:] + [(end_s, {})]):
            if message["value"]:
                state.barh(row, end - start, left=start, color=phases[message["value"]])
    state.set(yticks=range(len(tasks)), yticklabels=tasks, xlabel="simulated time [s]",
              title="/mission/phase/<Task> (orange measuring, green active)")
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print(f"wrote {out}")


if __name__ == "__main__":
    main(*sys.argv[1:])
