"""The flags ``orccad run`` and ``orccad sil`` share, and what they do with them.

Both commands run a mission through the run façade (:mod:`orccad_app.session`) and print the
same report: the same injections (``--inject``, ``--inject-from``), overrides (``--set``,
``--timing``), trace (``--trace``, ``--trace-format``), live views (``--foxglove``,
``--ros2-zenoh``), scheduling (``--scheduler``, ``--context-switch-us``, ``--bus-us``), a
real controller's delays (``--exchange-us``, ``--jitter-us``),
``--json``, and the same exit status. Only the standard library is imported at module level
(building the parser stays fast).
"""

from __future__ import annotations

import argparse
import math
import sys
from typing import Any

from orccad_app.commands.arguments import (bounded_int, checked_injection, delay_us,
                                           non_negative_int, seconds)

__all__ = ["add_run_flags", "check_run_flags", "run_options", "refuse_trace_over_inputs",
           "observe", "render"]


def _wall_seconds(text: str) -> float:
    """A wall-clock wait [s]: finite, in [0, 3600]."""
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not 0 <= value <= 3600:  # NaN fails too
        raise argparse.ArgumentTypeError(f"expected seconds in [0, 3600], got {text!r}")
    return value


def add_run_flags(parser: argparse.ArgumentParser) -> None:
    """Register the flags both commands take (see the module docstring)."""
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
    parser.add_argument("--exchange-us", type=delay_us, default=0, metavar="US",
                        help="model a real controller's I/O: the robot's ports exchanged every "
                             "US µs (a sensor up to US old, a torque applied up to US late; "
                             "the phase from the seed); default 0, the ideal exchange")
    parser.add_argument("--jitter-us", type=delay_us, default=0, metavar="US",
                        help="model a real controller's release jitter: each periodic release "
                             "late by a uniform draw in [0, US] µs (from the seed); default 0")


def check_run_flags(args: argparse.Namespace) -> None:
    """What the flags need, said before the file is loaded: a name for ``--trace`` and
    ``--inject-from``, and a ``--trace`` that is not a FIFO or a socket (opening one waits
    for a reader forever); ``--trace-format`` needs ``--trace``; rosbag2, ``--ros2-zenoh``
    and ``--foxglove`` their extras; ``--foxglove-port`` and ``--foxglove-wait`` need
    ``--foxglove``."""
    import os
    import stat

    from orccad_app.diagnostics import OrccadError

    for flag, value in (("--trace", args.trace), ("--inject-from", args.inject_from)):
        if value is not None and not value.strip():
            raise OrccadError(f"{flag}: an empty name (name a file, or leave the flag out)")
    try:
        mode = os.stat(args.trace).st_mode if args.trace else 0
    except OSError:
        mode = 0  # a new file (or an unwritable one: said when it is opened)
    if stat.S_ISFIFO(mode) or stat.S_ISSOCK(mode):
        raise OrccadError(f"--trace {args.trace}: a {'FIFO' if stat.S_ISFIFO(mode) else 'socket'}"
                          ", not a regular file (a trace is written to a file)")
    if args.trace_format is not None and not args.trace:
        raise OrccadError("--trace-format needs --trace")
    if args.trace_format == "rosbag2":
        from orccad_app.ros2 import require

        require("--trace-format rosbag2")
    if args.ros2_zenoh is not None:
        from orccad_app.ros2 import require
        from orccad_app.ros2.endpoint import check_endpoint

        require("--ros2-zenoh", zenoh=True)
        check_endpoint(args.ros2_zenoh)
    if (args.foxglove_port is not None or args.foxglove_wait is not None) and not args.foxglove:
        raise OrccadError("--foxglove-port and --foxglove-wait need --foxglove")
    if args.foxglove:
        from orccad_app.trace.foxglove_live import require_foxglove

        require_foxglove()


def refuse_trace_over_inputs(args: argparse.Namespace, source: Any) -> None:
    """Refuse a ``--trace`` that names one of the run's inputs: the .orc file, a file it
    imports, the ``--inject-from`` script (``source``: the loaded file)."""
    from orccad_app.commands.arguments import refuse_overwriting

    refuse_overwriting(args.trace, args.file, args.inject_from,
                       *(imported.path for imported in source.imported), flag="--trace")


def _warn_first_instant(injections) -> None:
    for injection in injections:
        if injection.time_ns == 0 and injection.fault is None:
            print(f"orccad: warning: --inject {injection.name}@0 is present in the mission's "
                  "first instant, where only 'immediate' tests see it (await, abort ... when "
                  "and each look from the next instant on)", file=sys.stderr)


def run_options(args: argparse.Namespace, realtime: float | None) -> Any:
    """The run's :class:`~orccad_app.session.RunOptions` from the command line (injections
    and overrides parsed: a malformed one is refused before the file is loaded); paced at
    ``realtime`` (simulated s per wall s, ``None``: as fast as possible; a live view paces at
    1 by default)."""
    from orccad_app.executive.delays import ControllerDelays
    from orccad_app.mission.overrides import PlanOverrides
    from orccad_app.session import InputScript, RunOptions

    injections = tuple(checked_injection(text) for text in args.inject)
    _warn_first_instant(injections)
    overrides = PlanOverrides.from_arguments(args.overrides, args.timing)
    live = args.foxglove or args.ros2_zenoh is not None
    return RunOptions(overrides=overrides, injections=injections,
                      script=InputScript.from_file(args.inject_from) if args.inject_from
                      else None,
                      seed=args.seed, until_s=args.until, scheduler=args.scheduler,
                      context_switch_ns=args.context_switch_us * 1000,
                      bus_transfer_ns=args.bus_us * 1000,
                      delays=ControllerDelays(args.exchange_us, args.jitter_us),
                      realtime=1.0 if live and realtime is None else realtime,
                      trace=args.trace, trace_format=args.trace_format, trace_file=args.file,
                      signals_end_run=True)


def _foxglove_wait_s(args: argparse.Namespace) -> float:
    return 60.0 if args.foxglove_wait is None else args.foxglove_wait


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


def _bridge(args: argparse.Namespace, session: Any) -> None:
    """``--ros2-zenoh``: the plant and the mission's inputs and outputs as ROS 2 topics."""
    from orccad_app.ros2.bridge import MissionBridge

    bridge = MissionBridge(session.run, [args.ros2_zenoh])

    def close() -> None:
        reached = bridge.bridge.reached()
        bridge.close()
        print(f"orccad: ROS 2: {bridge.raised} inputs raised, {bridge.applied} joint "
              "commands applied" + ("" if reached else f"; no Zenoh router or peer was "
                                                       f"reached at {args.ros2_zenoh}"),
              file=sys.stderr, flush=True)

    session.add_observer(bridge, close)
    print(f"orccad: ROS 2 over Zenoh via {args.ros2_zenoh} (domain "
          f"{bridge.bridge.domain_id}): /joint_states, /joint_commands, /orccad/input/*, "
          "/orccad/output/*", file=sys.stderr, flush=True)
    if not bridge.bridge.reached():
        print(f"orccad: warning: --ros2-zenoh {args.ros2_zenoh}: no Zenoh router or peer "
              "reached (is rmw_zenoh's router running? ros2 run rmw_zenoh_cpp rmw_zenohd); "
              "the run goes on, and connects if one comes", file=sys.stderr, flush=True)


def observe(args: argparse.Namespace, session: Any) -> Any:
    """The command's own observers of ``session``: a progress line on a terminal (never in a
    pipe or a file), the ``--ros2-zenoh`` bridge and the ``--foxglove`` stream; what to do
    when the run is about to start (wait for a Foxglove subscriber), or ``None``."""
    if sys.stderr.isatty():
        from orccad_app.mission.progress import ProgressLine

        progress = ProgressLine(sys.stderr, session.until_ns)
        session.add_observer(progress, progress.close)
    if args.ros2_zenoh is not None:
        _bridge(args, session)
    if args.foxglove:
        server = _foxglove(args, session.mission.name, session.plan)
        session.record(server)
        return lambda mission_run: _wait_for_foxglove(args, server, mission_run)
    return None


def render(args: argparse.Namespace, report: Any, extra: dict[str, Any] | None = None,
           lines: tuple[str, ...] = ()) -> int:
    """Print the report (text or JSON; ``extra`` keys added to the JSON object, ``lines``
    after the text) and what went wrong; the exit status."""
    from orccad_app.jsonout import dumps
    from orccad_app.mission.result import MissionStatus

    result = report.result
    if args.json:
        print(dumps({**report.as_dict(), **(extra or {})}, indent=2))
    else:
        print(report.text())
        for line in lines:
            print(line)
        if args.trace:
            print(f"Trace: {args.trace}")
    if result.interrupted:
        print("orccad: interrupted", file=sys.stderr)
        return 130
    if result.status is MissionStatus.RECOVERING and not args.json:
        print(f"orccad: mission aborted by {result.reason}, its 'on fatal' recovery cut by the "
              f"horizon (status recovering)", file=sys.stderr)
    elif result.status is not MissionStatus.DONE and not args.json:
        print(f"orccad: mission {result.status}: {result.reason}", file=sys.stderr)
    violated = report.violated
    if violated and not args.json:
        print(f"orccad: propert{'ies' if len(violated) > 1 else 'y'} violated on this run: "
              f"{', '.join(violated)}", file=sys.stderr)
    return report.exit_status
