"""Write docs/foxglove-layout.json: a Foxglove layout for traces of the arm's missions.

Built with the Foxglove SDK's layout types (``foxglove.layouts``, in the ``foxglove`` extra),
so the file is in the format the Foxglove app imports (*Layouts* → *Import from file*).
Panels, for ``missions/arm_recovery.orc`` (the topics are those of docs/executive.md):

- a **3D** panel following ``world``: the arm's geometry (``/scene``) on its frames (``/tf``);
- the **log** (``/log``: the mission's story);
- **set-point vs measure** for joints 1 and 2: the measured ``/plant/arm/q`` against the
  reference ``qd`` of each Robot-Task's trajectory module (Home, TrackPID, Park);
- the **gains**: ``/params/TrackPID/ctrl/kp`` (type-1 updates);
- the **verdicts**: every property's running verdict (1 true, 0 undecided, -1 false);
- the **mission's state**: State Transitions of each Robot-Task's phase and of the statements
  the automaton waits at.

Run from the repository's root: ``python docs/make_foxglove_layout.py`` (``--check``: exit 1
when the file differs from what this script writes).
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import foxglove.layouts as fl

OUT = Path(__file__).with_name("foxglove-layout.json")
TASK_TRAJECTORIES = {"Home": "/ports/Home_0/traj/qd", "TrackPID": "/ports/TrackPID/traj/qd",
                     "Park": "/ports/Park/traj/qd"}
"""Each Robot-Task's set-point topic in arm_recovery.orc (Home runs at two sites: Home_0)."""
PROPERTIES = ("home_before_tracking", "one_task_at_a_time", "retry_after_a_loss",
              "fatal_reported", "park_completes", "parked_before_done", "finished_once")


def _joint_plot(joint: int) -> fl.PlotPanel:
    series = [fl.PlotSeries(value=f"/plant/arm/q.value[{joint}]", label=f"q{joint + 1} measured")]
    series += [fl.PlotSeries(value=f"{topic}.value[{joint}]", label=f"{task} set-point",
                             line_style="dashed")
               for task, topic in TASK_TRAJECTORIES.items()]
    return fl.PlotPanel(title=f"joint {joint + 1}: set-point vs measure [rad]",
                        config=fl.PlotConfig(paths=series, show_legend=True, is_synced=True))


def layout() -> fl.Layout:
    """The layout (see the module docstring)."""
    three_d = fl.ThreeDeePanel(title="arm", config=fl.ThreeDeeConfig(
        follow_tf="world", topics={"/scene": fl.BaseRendererSceneUpdateTopicSettings(
            visible=True)}))
    log = fl.LogPanel(title="mission log", config=fl.LogConfig(topic_to_render="/log"))
    gains = fl.PlotPanel(title="gain kp (type-1 updates)", config=fl.PlotConfig(
        paths=[fl.PlotSeries(value="/params/TrackPID/ctrl/kp.value", label="TrackPID kp",
                             line_interpolation="step")], is_synced=True))
    verdicts = fl.PlotPanel(title="property verdicts (1 true, 0 undecided, -1 false)",
                            config=fl.PlotConfig(paths=[
                                fl.PlotSeries(value=f"/properties/{name}.value", label=name,
                                              line_interpolation="step")
                                for name in PROPERTIES], show_legend=True, is_synced=True))
    state = fl.StateTransitionsPanel(title="mission state", config=fl.StateTransitionsConfig(
        paths=[fl.StateTransitionsSeries(value=f"/mission/phase/{task}.phase", label=task)
               for task in TASK_TRAJECTORIES]
        + [fl.StateTransitionsSeries(value="/mission/state.at", label="waits at")],
        is_synced=True))
    left = fl.SplitContainer(direction="column", items=[
        fl.SplitItem(proportion=2, content=three_d), fl.SplitItem(proportion=1, content=log)])
    right = fl.SplitContainer(direction="column", items=[
        fl.SplitItem(content=_joint_plot(0)), fl.SplitItem(content=_joint_plot(1)),
        fl.SplitItem(content=gains), fl.SplitItem(content=verdicts),
        fl.SplitItem(content=state)])
    return fl.Layout(content=fl.SplitContainer(direction="row", items=[
        fl.SplitItem(proportion=1, content=left), fl.SplitItem(proportion=1, content=right)]))


def text() -> str:
    """The file's text: the layout as indented JSON."""
    return json.dumps(json.loads(layout().to_json()), indent=2) + "\n"


def main(argv: list[str]) -> int:
    if "--check" in argv:
        return 0 if OUT.read_text(encoding="utf-8") == text() else 1
    OUT.write_text(text(), encoding="utf-8")
    print(f"wrote {OUT}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
