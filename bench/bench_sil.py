"""Software-in-the-loop benchmark: lockstep SIL against ``orccad run``, and real-time release
lateness with and without SCHED_FIFO.

1. **Lockstep** (``orccad sil FILE --lockstep``) against the executive (``orccad run FILE``) on
   the same mission: simulated seconds per wall second of each, best of ``--repeat``, and the
   ratio executive / lockstep (how many times slower the controller process over its socket
   makes the run). The two reports are checked equal first.
2. **Real time** at 1 kHz: ``orccad sil missions/arm_pid.orc --realtime`` (4 s; the trajectory
   and the PID every 1 ms), once with the processor threads under SCHED_FIFO (where permitted)
   and once with ``ORCCAD_NO_FIFO=1``; per run the release lateness of ``TrackPID.ctrl``
   (median, p99, max), overruns and deadline misses, and the ratio of the p99s.
   Wall-clock figures depend on the machine's load: compare the two rows of one command.

    python bench/bench_sil.py [--repeat 3] [--mission missions/arm_pid.orc]

Needs: no extra; a C compiler (``gcc`` or ``cc``) for the controller it builds.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from orccad_app.pipeline import load, select_mission  # noqa: E402
from orccad_app.session import (ControllerOptions, Execution, RunOptions,  # noqa: E402
                                RunSession)


def _run(path: Path, execution: Execution = Execution.SIMULATED) -> tuple[float, dict]:
    """One run through the run façade (its Module-Tasks run as ``execution`` says; the
    controller built and started before the clock starts): its wall time [s] and its report
    without the wall time."""
    source = load(str(path))
    session = RunSession(source, select_mission(source, None),
                         RunOptions(execution=execution, controller=ControllerOptions(str(path))))
    start = time.perf_counter()
    report = session.execute().as_dict()
    wall = time.perf_counter() - start
    report.pop("wall_time_s")
    return wall, report


def lockstep_against_run(path: Path, repeat: int) -> None:
    best_run = best_sil = float("inf")
    expected = got = None
    for _ in range(repeat):
        wall, expected = _run(path)
        best_run = min(best_run, wall)
        wall, got = _run(path, Execution.LOCKSTEP)  # compiled once (cached)
        best_sil = min(best_sil, wall)
    assert got == expected, "lockstep and orccad run disagree"
    sim_s = expected["sim_time_s"]
    print(f"{path.name}: {sim_s:g} simulated s, reports equal")
    print(f"  orccad run         {sim_s / best_run:8.2f} sim s / wall s  ({best_run:.3f} s)")
    print(f"  orccad sil lockstep {sim_s / best_sil:7.2f} sim s / wall s  ({best_sil:.3f} s)")
    print(f"  ratio run / lockstep: {best_sil / best_run:.2f}× slower in lockstep")


def _realtime(fifo: bool) -> dict:
    env = dict(os.environ)
    if not fifo:
        env["ORCCAD_NO_FIFO"] = "1"
    done = subprocess.run([sys.executable, "-m", "orccad_app", "sil",
                           str(ROOT / "missions" / "arm_pid.orc"), "--realtime", "--json"],
                          capture_output=True, text=True, env=env, timeout=300)
    report = json.loads(done.stdout)
    timing = {t["module"]: t for t in report["controller"]["timing"]}["TrackPID.ctrl"]
    return {"status": report["status"], "warning": "SCHED_FIFO is not permitted" in done.stderr,
            **timing}


def realtime_lateness() -> None:
    rows = [("SCHED_FIFO", _realtime(True)), ("default policy", _realtime(False))]
    print("real time, TrackPID.ctrl at 1 kHz for 4 s (release lateness [µs]):")
    for name, row in rows:
        late = row["lateness_s"]
        policy = name + (" (not permitted: default)" if row["warning"] and name == "SCHED_FIFO"
                         else "")
        print(f"  {policy:<34} median {late['median'] * 1e6:7.1f}  p99 {late['p99'] * 1e6:8.1f}"
              f"  max {late['max'] * 1e6:9.1f}  overruns {row['overruns']:4d}  misses "
              f"{row['deadline_misses']:4d}  jobs {row['released']}  ({row['status']})")
    fifo, other = rows[0][1]["lateness_s"]["p99"], rows[1][1]["lateness_s"]["p99"]
    print(f"  p99 ratio default / SCHED_FIFO: {other / fifo:.2f}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--mission", default=str(ROOT / "missions" / "arm_pid.orc"))
    args = parser.parse_args()
    lockstep_against_run(Path(args.mission), args.repeat)
    realtime_lateness()


if __name__ == "__main__":
    main()
