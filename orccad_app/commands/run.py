"""``orccad run FILE``: run a mission in the timed executive against the MuJoCo plant.

::

    orccad run FILE [--mission M] [--until S] [--seed N] [--inject SIG@T ...]
                    [--inject-from SCRIPT]
                    [--set ROBOT.PARAM=V ...] [--timing TASK.MODULE.FIELD=MS ...]
                    [--realtime [FACTOR]] [--trace OUT.csv|OUT.mcap|DIR]
                    [--trace-format csv|mcap|rosbag2] [--json]
                    [--foxglove] [--foxglove-port PORT] [--foxglove-wait S]
                    [--scheduler fp|edf] [--context-switch-us US] [--bus-us US]

The mission's automaton (application + RTAs) runs in the loop with the Module-Tasks of its
Robot-Tasks on simulated processors and the robot's plant (:mod:`orccad_app.mission.run`).
Prints a report (``--json``: one object, see :mod:`orccad_app.trace.report`) with the verdict
of every ``property`` of the mission on this run (key ``properties``, see
:mod:`orccad_app.properties`). Exit status: 0 when the mission ends ``done`` and no property
is false on the run; 1 when it ends ``failed``, ``aborted`` or ``timeout``, or a property is
false (a
deadlock, a diverging plant or a failing module is ``failed``; the report and trace are still
written); 2 on bad input; 130 on Ctrl-C (the trace stays valid, the report is printed).
"""

from __future__ import annotations

import argparse
import math
import sys
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

from orccad_app.commands.arguments import (MAX_SECONDS, add_mission, bounded_int,
                                           factor, non_negative_int, refuse_overwriting,
                                           seconds)

__all__ = ["register", "run"]


def register(sub) -> None:
    parser = sub.add_parser("run", help="run a mission in the executive against the plant",
                            description="Run the mission in the timed executive (Module-Tasks "
                                        "on simulated processors, MuJoCo plant) and print a "
                                        "report.")
    parser.add_argument("file", nargs="?", metavar="FILE",
                        help="the .orc file (may also come after --inject specs)")
    add_mission(parser)
    parser.add_argument("--until", type=seconds, default=None, metavar="S",
                        help="simulated-time limit [s] (default 60, or the robot type's "
                             "longer run_horizon_s; at most one year); status 'timeout' if "
                             "the mission is still running then")
    parser.add_argument("--seed", type=non_negative_int, default=0, metavar="N",
                        help="seed of execution times and sensor noise (default 0)")
    parser.add_argument("--inject", action="extend", nargs="+", default=[], metavar="SIG@T",
                        help="raise input SIG (or SIG(value)) at simulated time T [s]; "
                             "ROBOT.FAULT=VALUE@T applies a plant fault (auv.leak=1@120); "
                             "several specs may follow one flag, or repeat the flag")
    parser.add_argument("--inject-from", metavar="SCRIPT",
                        help="raise the inputs of an input script (a counterexample written by "
                             "orccad check --counterexample) at its instants' times: one "
                             "reaction tick apart at least (see docs/verification.md)")
    parser.add_argument("--set", action="append", default=[], dest="overrides",
                        metavar="ROBOT.PARAM=V",
                        help="set a parameter the robot type declares (auv.cb_height_m=0.02) "
                             "or a sensor's noise (auv.depth.noise_std=0.05); repeat the flag "
                             "for several")
    parser.add_argument("--timing", action="append", default=[], metavar="T.M.F=MS",
                        help="set a module's period_ms, wcet_ms or bcet_ms at every run of "
                             "its Robot-Task (Survey.pilot.wcet_ms=2.5); repeat the flag for "
                             "several")
    parser.add_argument("--realtime", type=factor, nargs="?", const=1.0, metavar="FACTOR",
                        help="pace simulated time to the wall clock (× FACTOR in "
                             "[0.001, 1000], default 1) and report lateness")
    parser.add_argument("--trace", metavar="OUT", help="write a trace (.csv or .mcap; a "
                                                       "directory with --trace-format rosbag2)")
    parser.add_argument("--trace-format", choices=("csv", "mcap", "rosbag2"), default=None,
                        help="the trace's format (default: by OUT's suffix); rosbag2: a new "
                             "directory OUT, MCAP storage, CDR (needs pip install -e "
                             "'.[ros2]')")
    parser.add_argument("--json", action="store_true", help="print the report as JSON")
    parser.add_argument("--foxglove", action="store_true",
                        help="stream the run live to Foxglove over its WebSocket protocol on "
                             "127.0.0.1 (the MCAP trace's topics; paced at real time unless "
                             "--realtime says otherwise; needs pip install -e '.[foxglove]')")
    parser.add_argument("--foxglove-port", type=bounded_int(0, 65535), default=None,
                        metavar="PORT", help="the --foxglove server's port (default 8765; 0 "
                                             "picks a free one)")
    parser.add_argument("--foxglove-wait", type=_wall_seconds, default=None, metavar="S",
                        help="with --foxglove, wait at most S wall seconds for Foxglove to "
                             "subscribe before the run starts (default 60; 0 starts at once)")
    parser.add_argument("--ros2-zenoh", nargs="?", const="tcp/127.0.0.1:7447", default=None,
                        metavar="ENDPOINT",
                        help="(experimental) the robot's /joint_states and /joint_commands and "
                             "the mission's inputs and outputs as ROS 2 topics over Zenoh, in "
                             "rmw_zenoh's conventions, connecting to ENDPOINT only (default "
                             "tcp/127.0.0.1:7447, rmw_zenoh's router; no multicast); paced at "
                             "real time unless --realtime says otherwise; needs pip install "
                             "-e '.[ros2]'")
    parser.add_argument("--scheduler", choices=("fp", "edf"), default="fp",
                        help="scheduling policy of every processor (default fp)")
    parser.add_argument("--context-switch-us", type=bounded_int(0, 10**9), default=0,
                        metavar="US", help="context-switch overhead [µs] (default 0)")
    parser.add_argument("--bus-us", type=bounded_int(0, 10**9), default=0, metavar="US",
                        help="bus transfer time per message [µs] (default 0)")
    parser.set_defaults(func=run)


def _wall_seconds(text: str) -> float:
    """A wall-clock wait [s]: finite, in [0, 3600]."""
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not 0 <= value <= 3600:  # NaN fails too
        raise argparse.ArgumentTypeError(f"expected seconds in [0, 3600], got {text!r}")
    return value


def _file_after_injections(args: argparse.Namespace) -> str:
    """The .orc file: the positional argument, or the word after the --inject specs that is
    not one (``orccad run --inject A@1 FILE``: a spec always holds '@')."""
    if args.file is None and args.inject and "@" not in args.inject[-1]:
        args.file = args.inject.pop()
    if args.file is None:
        from orccad_app.diagnostics import OrccadError
        raise OrccadError("orccad run: the .orc file is missing (orccad run FILE ...)")
    return args.file


def _injection(text: str):
    """``--inject`` text → :class:`Injection`, its time checked finite and within a year."""
    from orccad_app.diagnostics import OrccadError
    from orccad_app.mission.injection import parse_injection

    when = text.rpartition("@")[2]
    try:
        time_s = float(when)
    except ValueError:
        time_s = 0.0  # parse_injection names the problem
    if not (time_s == time_s and abs(time_s) <= MAX_SECONDS):
        raise OrccadError(f"bad injection {text!r}: the time must be a number of seconds in "
                          f"[0, {MAX_SECONDS:.0f}] (one year)")
    return parse_injection(text)


def _check_values(injections, inputs) -> list:
    """Each injected value typed against its input: none for a pure input, one of the
    declared type (finite, integers within 64 bits, a vector as [x, y, ...]) for a valued
    one; fault values finite."""
    import math

    from orccad_app.diagnostics import OrccadError
    from orccad_app.mission.injection import typed_injections

    for injection in injections:
        value = injection.value
        if injection.fault and isinstance(value, float) and not math.isfinite(value):
            raise OrccadError(f"--inject {injection.name}: the value must be a finite number, "
                              f"got {value}")
    return typed_injections(injections, inputs)


def _warn_first_instant(injections) -> None:
    for injection in injections:
        if injection.time_ns == 0 and not injection.fault:
            print(f"orccad: warning: --inject {injection.name}@0 is present in the mission's "
                  "first instant, where only 'immediate' tests see it (await, abort ... when "
                  "and each look from the next instant on)", file=sys.stderr)


def _scripted(path: str, plan) -> list:
    """The injections of the input script ``path`` (see :mod:`orccad_app.mission.scripted`)."""
    from orccad_app.mission.scripted import script_injections
    from orccad_app.pipeline import read_source
    from orccad_app.reactive.script import parse_script

    instants = parse_script(read_source(path), path, plan.automaton.inputs)
    return script_injections(instants, plan.tick_ns)


def _foxglove(args: argparse.Namespace, mission: str, plan):
    """The live stream of ``--foxglove`` (its URL said on standard error)."""
    from orccad_app.trace import sensor_ports
    from orccad_app.trace.foxglove_live import DEFAULT_PORT, open_foxglove

    port = DEFAULT_PORT if args.foxglove_port is None else args.foxglove_port
    live = open_foxglove(port, {"mission": mission, "file": args.file, "seed": str(args.seed)},
                         sensor_ports(plan))
    wait_s = _foxglove_wait_s(args)
    print(f"orccad: streaming to Foxglove on {live.url} (in Foxglove: Open connection, "
          "Foxglove WebSocket)" + (f"; the run starts when Foxglove subscribes (at most "
                                   f"{wait_s:g} s from now)" if wait_s > 0 else ""),
          file=sys.stderr, flush=True)
    return live


def _check_trace_format(args: argparse.Namespace) -> None:
    """``--trace-format`` needs ``--trace``; rosbag2 needs its extra (said before the run)."""
    from orccad_app.diagnostics import OrccadError

    if args.trace_format is not None and not args.trace:
        raise OrccadError("--trace-format needs --trace")
    if args.trace_format == "rosbag2":
        from orccad_app.ros2 import require

        require("--trace-format rosbag2")


def _open_trace(args: argparse.Namespace, mission: str, plan) -> Any:
    """The trace writer of ``--trace`` (and ``--trace-format``)."""
    from orccad_app.trace import open_trace, sensor_ports

    metadata = {"mission": mission, "file": args.file, "seed": str(args.seed)}
    if args.trace_format == "rosbag2":
        from orccad_app.ros2.bag import Rosbag2TraceWriter

        return Rosbag2TraceWriter(args.trace, metadata, sensor_ports(plan))
    return open_trace(args.trace, metadata, sensor_ports(plan), args.trace_format)


def _foxglove_wait_s(args: argparse.Namespace) -> float:
    return 60.0 if args.foxglove_wait is None else args.foxglove_wait


def _wait_for_foxglove(args: argparse.Namespace, live: Any, mission_run: Any) -> None:
    """Wait for a Foxglove subscriber (``--foxglove-wait``); Ctrl-C or SIGTERM meanwhile end
    the run before it starts (``mission_run.abort``: its report and a valid trace are still
    written)."""
    import time

    wait_s = _foxglove_wait_s(args)
    if wait_s <= 0:
        return
    deadline = time.monotonic() + wait_s
    while not mission_run.stopping:
        left = deadline - time.monotonic()
        if left <= 0:
            print("orccad: no Foxglove client yet: the run starts", file=sys.stderr, flush=True)
            return
        if live.wait_for_client(min(left, 0.1)):
            return


def _verdict_samples(monitor: Any) -> Any:
    """Every property's verdict on the run so far, for the trace's ``/properties`` topics."""
    from orccad_app.trace import VerdictSample

    def samples() -> list:
        return [VerdictSample(r.name, r.verdict.value, r.robustness, r.unit, r.samples)
                for r in monitor.running()]
    return samples


def _processors(plan, args: argparse.Namespace) -> list:
    from orccad_app.executive.processor import Processor

    return [Processor(name, args.scheduler, args.context_switch_us * 1000)
            for name in plan.processor_names]


def _terminate_like_ctrl_c() -> None:
    """SIGTERM ends the run as Ctrl-C does (status aborted, report printed, trace complete)
    instead of killing the process mid-write."""
    import signal
    import threading

    from orccad_app.mission.run import Terminated

    if threading.current_thread() is not threading.main_thread():
        return  # signal handlers belong to the main thread (the TUI runs elsewhere)

    def terminated(signum: int, frame: object) -> None:
        raise Terminated

    signal.signal(signal.SIGTERM, terminated)


@contextmanager
def _signals_end_the_run(mission_run: Any) -> Iterator[None]:
    """While the run goes, Ctrl-C and SIGTERM end it after the current event (status aborted,
    report printed, trace complete: nothing is cut mid-sample); a second one interrupts at
    once."""
    import signal
    import threading

    from orccad_app.mission.run import INTERRUPTED, TERMINATED

    if threading.current_thread() is not threading.main_thread():
        yield
        return
    reasons = {signal.SIGINT: INTERRUPTED, signal.SIGTERM: TERMINATED}

    def on_signal(signum: int, frame: object) -> None:
        if mission_run.stopping:
            raise KeyboardInterrupt
        mission_run.abort(reasons[signal.Signals(signum)])

    previous = {sent: signal.signal(sent, on_signal) for sent in reasons}
    try:
        yield
    finally:
        for sent, handler in previous.items():
            signal.signal(sent, handler)


def run(args: argparse.Namespace) -> int:
    from orccad_app.executive.bus import Bus
    from orccad_app.jsonout import dumps
    from orccad_app.mission.overrides import PlanOverrides, plan_with_overrides
    from orccad_app.mission.run import MissionRun, run_horizon_s
    from orccad_app.pipeline import load, select_mission
    from orccad_app.properties import PropertyMonitor, results_dict
    from orccad_app.properties.report import format_properties
    from orccad_app.trace import InjectionRecord, format_report, report_dict, trace_recorder

    _file_after_injections(args)
    _terminate_like_ctrl_c()
    _check_trace_format(args)
    if args.ros2_zenoh is not None:
        from orccad_app.ros2 import require

        require("--ros2-zenoh", zenoh=True)
    if (args.foxglove_port is not None or args.foxglove_wait is not None) and not args.foxglove:
        from orccad_app.diagnostics import OrccadError
        raise OrccadError("--foxglove-port and --foxglove-wait need --foxglove")
    if args.foxglove:  # before the run is planned: a missing extra is said at once
        from orccad_app.trace.foxglove_live import require_foxglove

        require_foxglove()
    injections = [_injection(text) for text in args.inject]
    _warn_first_instant(injections)
    overrides = PlanOverrides.from_arguments(args.overrides, args.timing)
    refuse_overwriting(args.trace, args.file)
    source = load(args.file)
    source.print_warnings()
    mission = select_mission(source, args.mission)
    plan = plan_with_overrides(source, mission, overrides)
    injections = _check_values(injections, plan.automaton.inputs)
    injected = [InjectionRecord(i.time_ns, i.name, i.value, i.fault) for i in injections]
    if args.inject_from:
        scripted = _scripted(args.inject_from, plan)
        injections += scripted
        injected += [InjectionRecord(i.time_ns, i.name, i.value, False,
                                     f"--inject-from {args.inject_from}") for i in scripted]
    writer = None
    until_s = min(args.until if args.until is not None else run_horizon_s(plan, 60.0),
                  MAX_SECONDS)
    mission_run = MissionRun(plan, seed=args.seed, until_ns=int(round(until_s * 1e9)),
                             injections=injections, processors=_processors(plan, args),
                             bus=Bus(transfer_ns=args.bus_us * 1000),
                             realtime=1.0 if (args.foxglove or args.ros2_zenoh is not None)
                             and args.realtime is None else args.realtime)
    monitor = PropertyMonitor(source.program, mission, mission_run)
    progress = None
    if sys.stderr.isatty():  # a progress line on long runs, never in a pipe or a file
        from orccad_app.mission.progress import ProgressLine

        progress = ProgressLine(sys.stderr, mission_run.until_ns)
        mission_run.add_observer(progress)
    verdicts = _verdict_samples(monitor)
    if args.trace:
        writer = trace_recorder(_open_trace(args, mission.name, plan), mission_run,
                                verdicts=verdicts)
        mission_run.add_observer(writer)
    bridge = None
    if args.ros2_zenoh is not None:
        from orccad_app.ros2.bridge import MissionBridge

        bridge = MissionBridge(mission_run, [args.ros2_zenoh])
        mission_run.add_observer(bridge)
        print(f"orccad: ROS 2 over Zenoh via {args.ros2_zenoh} (domain "
              f"{bridge.bridge.domain_id}): /joint_states, /joint_commands, /orccad/input/*, "
              "/orccad/output/*", file=sys.stderr, flush=True)
    live = server = None
    if args.foxglove:
        server = _foxglove(args, mission.name, plan)
        live = trace_recorder(server, mission_run, verdicts=verdicts)
        mission_run.add_observer(live)
    try:
        try:
            with _signals_end_the_run(mission_run):
                if server is not None:
                    _wait_for_foxglove(args, server, mission_run)
                result = mission_run.run()
        finally:
            if progress is not None:
                progress.close()
            if writer is not None:
                writer.close()
            if live is not None:
                live.close()
            if bridge is not None:
                bridge.close()
                print(f"orccad: ROS 2: {bridge.raised} inputs raised, {bridge.applied} joint "
                      "commands applied", file=sys.stderr, flush=True)
    except OSError as error:  # the trace's disk is full or gone
        if not args.trace:
            raise
        from orccad_app.diagnostics import OrccadError
        raise OrccadError(f"{args.trace}: cannot write the trace: "
                          f"{error.strerror or error}") from None
    injected.sort(key=lambda record: record.time_ns)
    verdicts = monitor.results()
    if args.json:
        report = report_dict(result, injected)
        report["properties"] = results_dict(verdicts)
        print(dumps(report, indent=2))
    else:
        print(format_report(result, injected))
        if verdicts:
            print("\n".join(format_properties(verdicts)))
        if args.trace:
            print(f"Trace: {args.trace}")
    if result.interrupted:
        print("orccad: interrupted", file=sys.stderr)
        return 130
    if result.status == "recovering" and not args.json:
        print(f"orccad: mission aborted by {result.reason}, its 'on fatal' recovery cut by the "
              f"horizon (status recovering)", file=sys.stderr)
    elif result.status != "done" and not args.json:
        print(f"orccad: mission {result.status}: {result.reason}", file=sys.stderr)
    violated = [v.name for v in verdicts if v.verdict.value == "false"]
    if violated and not args.json:
        print(f"orccad: propert{'ies' if len(violated) > 1 else 'y'} violated on this run: "
              f"{', '.join(violated)}", file=sys.stderr)
    return max(result.exit_status, 1 if violated else 0)
