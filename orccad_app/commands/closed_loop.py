"""The closed-loop comparison of control laws, without the executive.

``python -m orccad_app.commands.closed_loop`` tracks the cosine reference of RR-1801 eq. 9-10
with each law (:func:`orccad_app.control.closed_loop.simulate`) and prints the RMS and maximum
tracking errors; exit status 1 if a law is unstable, 2 on bad arguments.
"""

from __future__ import annotations

import argparse
import math
import sys
from collections.abc import Sequence

from orccad_app.control.closed_loop import simulate
from orccad_app.control.spec import resolve
from orccad_app.diagnostics import OrccadError
from orccad_app.plugin_host.host import PluginHost

__all__ = ["main"]


def _arguments(argv: Sequence[str] | None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(
        prog="python -m orccad_app.control.closed_loop",
        description="Track q_d = q0 (1 + cos(omega t)) with each law on a robot's plant.")
    parser.add_argument("--robot", default="arm3dof", help="robot type (default arm3dof)")
    parser.add_argument("--laws", nargs="+", default=["pid", "computed_torque"])
    parser.add_argument("--kp", type=float, default=400.0, help="kp (default 400)")
    parser.add_argument("--kv", type=float, default=40.0, help="kv (default 40)")
    parser.add_argument("--ki", type=float, default=10.0, help="PID's ki (default 10)")
    parser.add_argument("--q0", type=float, nargs="+", default=[0.5, 0.5, 0.5])
    parser.add_argument("--omega", type=float, default=math.pi, help="[rad/s]")
    parser.add_argument("--duration", type=float, default=4.0, help="[s] (default 4)")
    parser.add_argument("--rate", type=float, default=1000.0, help="[Hz] (default 1000)")
    parser.add_argument("--model", choices=("identity", "pinocchio", "perturbed"),
                        help="model of the laws that take one (default: the law's)")
    parser.add_argument("--perturbation", type=float,
                        help="relative model error of --model perturbed (default 0.1)")
    return parser.parse_args(argv)


def _law_args(name: str, args: argparse.Namespace) -> dict[str, object]:
    """The command line's gains in the parameters of law ``name``."""
    if name == "generic":  # eq. 5: kv = k, kp = k mu
        gains: dict[str, object] = {"k": args.kv, "mu": args.kp / args.kv}
    else:
        gains = {"kp": args.kp, "kv": args.kv}
    if name == "pid":
        gains["ki"] = args.ki
    if name != "pid" and args.model is not None:
        gains["model"] = args.model
    if name != "pid" and args.perturbation is not None:
        gains["perturbation"] = args.perturbation
    return gains


def main(argv: Sequence[str] | None = None) -> int:
    """Print RMS and maximum tracking errors of each law; exit 1 if one is unstable."""
    args = _arguments(argv)
    try:
        host = PluginHost.load()
        robot = host.robot_types.get(args.robot)
        task = resolve(host, "task function", ("joint_tracking", {
            "trajectory": ("cosine", {"q0": args.q0, "omega": args.omega})}))
        results = []
        for name in args.laws:
            law_spec = resolve(host, "control law", (name, _law_args(name, args)))
            law = law_spec.build(robot, task.build(robot))
            results.append(simulate(law, args.duration, args.rate))
    except OrccadError as error:
        print(error.format(), file=sys.stderr)
        return 2
    print(f"{args.robot}: q_d = {args.q0} (1 + cos({args.omega:g} t)), "
          f"{args.duration:g} s at {args.rate:g} Hz, kp = {args.kp:g}, kv = {args.kv:g}")
    print(f"{'law':<16} {'RMS e [rad]':>12} {'max |e| [rad]':>14} {'peak τ [N·m]':>13} "
          f"{'saturated':>9}  stable")
    for result in results:
        print(f"{result.law:<16} {result.rms_error:>12.3e} {result.max_error:>14.3e} "
              f"{result.peak_torque:>13.1f} {result.saturation_ratio:>9.1%}  "
              f"{'yes' if result.stable else 'NO'}")
    if len(results) >= 2 and results[-1].rms_error > 0:
        print(f"RMS ratio {results[0].law} / {results[-1].law}: "
              f"{results[0].rms_error / results[-1].rms_error:.1f}")
    return 0 if all(result.stable for result in results) else 1


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
