"""Mission-run benchmark: ``orccad run missions/arm_pid.orc`` against a bare Python loop.

The executive side is what ``orccad run missions/arm_pid.orc`` does after compiling: the
mission's automaton reacting every millisecond, five Module-Tasks (trajectory, PID, joint
limits, tracking error, torque saturation) on a fixed-priority processor with their execution
times, the MuJoCo arm advanced between events, statistics (no trace). The baseline, in the same
command, is the tightest honest loop doing the same control: for 4000 periods of 1 ms, sample
the same trajectory, run the same PID object (``law.command``), hold the torque and
``mj_step`` the same MJCF arm — no executive, no observers, no automaton.

Both track the same trajectory; the script checks that their RMS errors agree within 1 % and
prints simulated seconds per wall second of each, and the ratio bare / executive (how many
times slower the executive is; the target is at most 3). Each side runs ``--repeat`` times and
the best time is kept (the machine's load varies; the ratio of bests is stable).

    python bench/bench_run.py [--repeat 5]

Exit status 0 when every target is met, 1 when one is MISSED (2 is bad input, as for
orccad).

Needs: no extra: ORCCAD's own dependencies.
"""

from __future__ import annotations

import argparse
import functools
import math
import time
from pathlib import Path

import mujoco
import numpy as np

from orccad_app.control.spec import resolve
from orccad_app.mission.plan import plan_mission
from orccad_app.mission.run import MissionRun
from orccad_app.pipeline import load, select_mission
from orccad_app.plugin_host.host import PluginHost

MISSION = Path(__file__).resolve().parents[1] / "missions" / "arm_pid.orc"
DURATION_S = 4.0
TARGET = 3.0
CLOCK = time.perf_counter
"""The clock of the timings (bench_executive.py may set ``time.process_time``)."""



@functools.cache
def _host() -> PluginHost:
    """The installed plugins, loaded once for the whole benchmark (outside the timings)."""
    return PluginHost.load()

def run_executive(plan) -> tuple[float, float]:
    """(wall time [s], RMS tracking error [rad]) of one executive run."""
    start = CLOCK()
    result = MissionRun(plan).run()
    wall = CLOCK() - start
    assert result.status == "done", (result.status, result.reason)
    return wall, result.rms_error()


def run_bare(host) -> tuple[float, float]:
    """(wall time [s], RMS tracking error [rad]) of the bare loop."""
    robot = host.robot_types.get("arm3dof")
    task_spec = resolve(host, "task function", ("joint_tracking", {
        "trajectory": ("cosine", {"q0": [0.5, 0.5, 0.5], "omega": math.pi})}))
    law = resolve(host, "control law", ("pid", {"kp": 400.0, "kv": 40.0, "ki": 10.0})
                  ).build(robot, task_spec.build(robot))
    trajectory = task_spec.build(robot)
    model = mujoco.MjModel.from_xml_path(str(robot.mjcf_path))
    data = mujoco.MjData(model)
    data.qpos[:] = trajectory.reference(0.0).pos
    mujoco.mj_forward(model, data)
    law.reset()
    steps = int(round(DURATION_S / model.opt.timestep))
    low, high = model.actuator_ctrlrange[:, 0], model.actuator_ctrlrange[:, 1]
    sum_sq = 0.0
    start = CLOCK()
    for k in range(steps):
        t = k * model.opt.timestep
        q, qdot = data.qpos.copy(), data.qvel.copy()
        out = law.command(t, q, qdot, trajectory.reference(t))
        data.ctrl[:] = np.clip(out.tau, low, high)
        mujoco.mj_step(model, data)
        sum_sq += float(np.dot(out.e, out.e))
    wall = CLOCK() - start
    return wall, math.sqrt(sum_sq / (3 * steps))


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--repeat", type=int, default=5, help="runs per side (best kept)")
    args = parser.parse_args()
    host = _host()
    source = load(MISSION)
    plan = plan_mission(source, select_mission(source, None))
    executive = [run_executive(plan) for _ in range(args.repeat)]
    bare = [run_bare(host) for _ in range(args.repeat)]
    exec_wall, exec_rms = min(executive)
    bare_wall, bare_rms = min(bare)
    assert abs(exec_rms - bare_rms) <= 0.01 * bare_rms, (exec_rms, bare_rms)
    ratio = exec_wall / bare_wall
    print(f"arm_pid, {DURATION_S:g} s simulated, best of {args.repeat}")
    print(f"  executive : {exec_wall:.3f} s wall  {DURATION_S / exec_wall:6.2f} sim s / wall s"
          f"  RMS e {exec_rms:.4e} rad")
    print(f"  bare loop : {bare_wall:.3f} s wall  {DURATION_S / bare_wall:6.2f} sim s / wall s"
          f"  RMS e {bare_rms:.4e} rad")
    print(f"  executive / bare: {ratio:.2f}x slower (target <= {TARGET:g}x): "
          f"{'met' if ratio <= TARGET else 'MISSED'}")
    return 0 if ratio <= TARGET else 1


if __name__ == "__main__":
    raise SystemExit(main())
