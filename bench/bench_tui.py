"""TUI live-run benchmark: ``orccad tui MISSION --run --speed max`` against ``orccad run MISSION``.

Both run the same mission to its end in this process, one after the other, ``--repeat`` times
each (the best time of each is kept: the machine's load varies, the ratio of bests is stable):

- **CLI**: ``orccad run MISSION`` through the command's own entry point (plan, run with the
  property monitor, report; output discarded);
- **TUI**: the console app (Textual, headless through ``App.run_test`` at 160×48: every widget
  laid out and rendered as on a terminal) started with the mission running at "max" speed,
  timed from the moment the run starts until the report screen is up.

It prints both times and the ratio TUI / CLI; the target (issue 26) is at most 1.5. It also
prints the CPU time each took (the TUI's: the console's process and the run's own process,
:mod:`orccad_app.tui.run_process`), whose ratio says what the live view costs in work, the
machine's load aside (on a loaded machine the wall ratio approaches it: the two processes then
share the CPU time the machine gives this command).

    python bench/bench_tui.py [--mission missions/arm_pid.orc] [--repeat 3]

Exit status 0 when every target is met, 1 when one is MISSED (2 is bad input, as for
orccad).

Needs: no extra: ORCCAD's own dependencies.
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import io
import os
import resource
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
MISSION = ROOT / "missions" / "arm_pid.orc"
TARGET = 1.5


def _cpu_s() -> float:
    """CPU time [s] of this process and its ended children so far."""
    own = resource.getrusage(resource.RUSAGE_SELF)
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + children.ru_utime + children.ru_stime


def time_cli(mission: str) -> tuple[float, float]:
    """Wall and CPU time [s] of ``orccad run MISSION`` (its output discarded)."""
    from orccad_app.cli import main

    start, cpu = time.perf_counter(), _cpu_s()
    with contextlib.redirect_stdout(io.StringIO()):
        status = main(["run", mission])
    wall = time.perf_counter() - start
    assert status == 0, status
    return wall, _cpu_s() - cpu


async def _tui(mission: str) -> tuple[float, float]:
    from orccad_app.tui.app import OrccadApp
    from orccad_app.tui.screens.report import ReportScreen

    app = OrccadApp([], selected=mission, speed=None, run_now=False)
    async with app.run_test(size=(160, 48)) as pilot:
        await pilot.pause()
        start, cpu = time.perf_counter(), _cpu_s()
        app.start_run(mission, None)
        while not (isinstance(app.screen, ReportScreen) and app.screen.query("#report-text")):
            await asyncio.sleep(0.01)
        wall, cpu = time.perf_counter() - start, _cpu_s() - cpu  # the run's process ended
        await pilot.pause(0.2)  # let the report screen finish mounting before the app exits
        assert app.session.result.status == "done", app.session.result.status
    return wall, cpu


def time_tui(mission: str) -> tuple[float, float]:
    """Wall and CPU time [s] of the console's live run of ``mission`` at max speed, from its
    start to its report on screen."""
    return asyncio.run(_tui(mission))


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--mission", default=str(MISSION.relative_to(ROOT)))
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    time_cli(args.mission)  # warm: imports, plugins, MuJoCo models
    clis = [time_cli(args.mission) for _ in range(args.repeat)]
    tuis = [time_tui(args.mission) for _ in range(args.repeat)]
    cli, tui = min(wall for wall, _ in clis), min(wall for wall, _ in tuis)
    cli_cpu, tui_cpu = min(cpu for _, cpu in clis), min(cpu for _, cpu in tuis)
    ratio = tui / cli
    print(f"{args.mission}: orccad run {cli:.2f} s, orccad tui at max speed {tui:.2f} s "
          f"(start to report)")
    print(f"ratio TUI / CLI: {ratio:.2f} (target <= {TARGET:g}: "
          f"{'met' if ratio <= TARGET else 'MISSED'})")
    print(f"CPU time: orccad run {cli_cpu:.2f} s, orccad tui {tui_cpu:.2f} s (both of its "
          f"processes): ratio {tui_cpu / cli_cpu:.2f}")
    print(f"load average during the command: {os.getloadavg()[0]:.1f} "
          f"on {os.cpu_count()} CPUs")
    return 0 if ratio <= TARGET else 1


if __name__ == "__main__":
    sys.exit(main())
