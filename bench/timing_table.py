"""Tracking error against the control period and execution time (RR-1801 §6.2), in the executive.

Default: runs missions/arm_computed_torque.orc and missions/arm_pid.orc (4 s of the paper's
trajectory) with the control law's period ``T`` and execution time ``C`` varied (the trajectory
module keeps the period, with zero execution time) and prints the RMS tracking error of each run
as a Markdown table for docs/control.md. A run whose mission fails (``TrackingLost``: the error
exceeded 0.2 rad) is marked so.

``--multirate``: runs missions/arm_computed_torque_multirate.orc (computed torque split into a
1 ms feedback Module-Task and a dynamic-model Module-Task) with the model's update period
varied, and prints the tracking error (max and RMS [rad]) with the execution times, where the
model runs (its processor, the protocol of the ``M``, ``N`` ports, bus messages) and the
worst response times, for docs/control.md.

    python bench/timing_table.py [--periods 1 2 3 4] [--fractions 0 0.25 0.5 0.75]
    python bench/timing_table.py --multirate [--model-periods 1 2 5 10 20]
"""

from __future__ import annotations

import argparse
import re
import tempfile
from dataclasses import dataclass
from pathlib import Path

from orccad_app.executive.bus import Bus
from orccad_app.mission.plan import plan_mission
from orccad_app.mission.result import RunResult
from orccad_app.mission.run import MissionRun
from orccad_app.pipeline import load, select_mission

ROOT = Path(__file__).resolve().parents[1]
MISSIONS = {"computed_torque": ROOT / "missions" / "arm_computed_torque.orc",
            "pid": ROOT / "missions" / "arm_pid.orc"}
MULTIRATE = ROOT / "missions" / "arm_computed_torque_multirate.orc"
MODEL_LINE = re.compile(r"module model : dynamic_model\s+period [0-9.]+ ms\s+wcet [0-9.]+ ms"
                        r"\s+on cpu\d priority \d")


def _run(path: Path, text: str, bus: Bus | None = None) -> RunResult:
    with tempfile.TemporaryDirectory() as folder:
        edited = Path(folder) / path.name
        edited.write_text(text, encoding="utf-8")
        source = load(edited)
        return MissionRun(plan_mission(source, select_mission(source, None)), bus=bus).run()


def rms_error(path: Path, period_ms: float, wcet_ms: float) -> str:
    """The run's RMS error [rad] as text, or its failure."""
    text = path.read_text(encoding="utf-8")
    text = re.sub(r"(module traj : trajectory\s+)period 1 ms wcet [0-9.]+ ms",
                  rf"\g<1>period {period_ms:g} ms wcet 0 ms", text)
    text = re.sub(r"(module ctrl : control_law\s+)period 1 ms wcet [0-9.]+ ms",
                  rf"\g<1>period {period_ms:g} ms wcet {wcet_ms:g} ms", text)
    result = _run(path, text)
    if result.status != "done":
        return f"{result.reason} at {result.sim_time_ns / 1e9:g} s"
    return f"{result.rms_error():.3e}"


@dataclass(frozen=True)
class MultirateRow:
    """One run of the split computed torque.

    :param model_period_ms: the dynamic model's period [ms].
    :param model_wcet_ms: its execution time [ms].
    :param processor: its processor (``cpu0``: beside the feedback; ``cpu1``: across the bus).
    :param protocol: the protocol of ``model.M -> ctrl.M`` and ``model.N -> ctrl.N``.
    :param status: the mission's status (``done``).
    :param max_error: max |e| over the run [rad].
    :param rms_error: RMS e over the run [rad].
    :param ctrl_response_ms: the feedback Module-Task's worst response [ms].
    :param model_response_ms: the model Module-Task's worst response [ms].
    :param ctrl_misses: the feedback Module-Task's deadline misses.
    :param bus_messages: messages over the bus.
    """

    model_period_ms: float
    model_wcet_ms: float
    processor: str
    protocol: str
    status: str
    max_error: float
    rms_error: float
    ctrl_response_ms: float
    model_response_ms: float
    ctrl_misses: int
    bus_messages: int


def multirate_run(period_ms: float, wcet_ms: float = 2.0, processor: str = "cpu1",
                  protocol: str = "asyn/asyn", bus_us: float = 0.0) -> MultirateRow:
    """Run the split computed torque with the model at ``period_ms`` / ``wcet_ms`` on
    ``processor``, its ``M``, ``N`` ports under ``protocol``, a bus message taking ``bus_us``."""
    text = MULTIRATE.read_text(encoding="utf-8")
    text, found = MODEL_LINE.subn(f"module model : dynamic_model period {period_ms:g} ms "
                                  f"wcet {wcet_ms:g} ms on {processor} "
                                  f"priority {1 if processor != 'cpu0' else 4}", text)
    assert found == 1, "the model line of the multirate mission changed"
    for port in ("M", "N"):
        text = text.replace(f"-> ctrl.{port}       : asyn/asyn",
                            f"-> ctrl.{port}       : {protocol}")
    result = _run(MULTIRATE, text, Bus(transfer_ns=round(bus_us * 1000)))
    summary = result.robot_tasks[0].errors.summary() if result.robot_tasks else None
    tasks = result.stats.tasks
    return MultirateRow(period_ms, wcet_ms, processor, protocol, result.status,
                        summary["max"] if summary else float("nan"),
                        summary["rms"] if summary else float("nan"),
                        tasks["TrackCTMultirate.ctrl"].response_max_ns / 1e6,
                        tasks["TrackCTMultirate.model"].response_max_ns / 1e6,
                        tasks["TrackCTMultirate.ctrl"].deadline_misses,
                        result.stats.bus.messages if result.stats.bus else 0)


def multirate_table(periods: list[float], bus_us: float) -> str:
    """The Markdown tables of docs/control.md: error against the model period; then, at
    10 ms, where the model runs and over which protocol."""
    lines = ["| model period | max \\|e\\| [rad] | RMS e [rad] | ctrl R max [ms] | "
             "model R max [ms] | ctrl misses | bus messages | status |",
             "|---|---|---|---|---|---|---|---|"]
    for period in periods:
        row = multirate_run(period, min(2.0, period / 2), "cpu1", "asyn/asyn", bus_us)
        lines.append(_line(f"{period:g} ms", row))
    lines += ["", "| model at 10 ms: processor, protocol | max \\|e\\| [rad] | RMS e [rad] | "
              "ctrl R max [ms] | model R max [ms] | ctrl misses | bus messages | status |",
              "|---|---|---|---|---|---|---|---|"]
    for processor, protocol in (("cpu0", "asyn/asyn"), ("cpu1", "asyn/asyn"),
                                ("cpu1", "asyn/synD"), ("cpu1", "asyn/synDF")):
        row = multirate_run(10.0, 2.0, processor, protocol, bus_us)
        lines.append(_line(f"{processor}, `{protocol}`", row))
    return "\n".join(lines)


def _line(label: str, row: MultirateRow) -> str:
    return (f"| {label} | {row.max_error:.3e} | {row.rms_error:.3e} | "
            f"{row.ctrl_response_ms:.3g} | {row.model_response_ms:.3g} | {row.ctrl_misses} | "
            f"{row.bus_messages} | "
            f"{row.status} |")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--periods", type=float, nargs="+", default=[1, 2, 3, 4])
    parser.add_argument("--fractions", type=float, nargs="+", default=[0, 0.25, 0.5, 0.75])
    parser.add_argument("--multirate", action="store_true",
                        help="the split computed torque: error against the model period")
    parser.add_argument("--model-periods", type=float, nargs="+", default=[1, 2, 5, 10, 20])
    parser.add_argument("--bus-us", type=float, default=50.0,
                        help="transfer time of one bus message [µs] (--multirate)")
    args = parser.parse_args()
    if args.multirate:
        print(f"\nsplit computed torque ({MULTIRATE.relative_to(ROOT)}): feedback 1 ms / "
              f"0.2 ms on cpu0, model C = min(2 ms, T/2) (on cpu0: priority 4, below the others), bus {args.bus_us:g} µs/message\n")
        print(multirate_table(args.model_periods, args.bus_us))
        return 0
    for law, path in MISSIONS.items():
        print(f"\n{law}: RMS tracking error [rad]\n")
        print("| T \\ C | " + " | ".join(f"{f:g} T" for f in args.fractions) + " |")
        print("|---|" + "---|" * len(args.fractions))
        for period in args.periods:
            cells = [rms_error(path, period, fraction * period) for fraction in args.fractions]
            print(f"| {period:g} ms | " + " | ".join(cells) + " |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
