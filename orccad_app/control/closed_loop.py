"""Closed-loop check of a control law on a robot's MuJoCo plant, without the executive.

The law runs at ``rate_hz`` with a zero-order hold on the torque; the plant integrates at
the MJCF timestep (1 ms for ``arm3dof``). This is the continuous-time design check of
RR-1801 §3.1 before the time-constrained specification: no processors, no delays.

Reproduce the figures of ``docs/control.md``::

    python -m orccad_app.control.closed_loop            # PID vs computed torque, 4 s, 1 kHz
    python -m orccad_app.control.closed_loop --kp 400 --kv 40 --ki 10 --duration 4
"""

from __future__ import annotations

import argparse
import math
import sys
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from orccad_app.control.errors import ControlError
from orccad_app.control.laws.base import ControlLaw
from orccad_app.control.physics import RobotPhysics

__all__ = ["ClosedLoopResult", "simulate", "main"]


@dataclass(frozen=True)
class ClosedLoopResult:
    """Samples at each control instant and summary figures.

    ``rms_error`` [rad] is :math:`\\sqrt{\\mathrm{mean}(e^2)}` over every sample and
    component; ``stable`` means every value stayed finite and ``max_error`` below
    ``bound`` [rad].
    """

    law: str
    times: np.ndarray
    q: np.ndarray
    qd: np.ndarray
    errors: np.ndarray
    tau: np.ndarray
    saturated: np.ndarray
    bound: float

    @property
    def rms_error(self) -> float:
        """RMS tracking error over time and components [rad]."""
        return float(np.sqrt(np.mean(self.errors ** 2)))

    @property
    def rms_error_per_joint(self) -> np.ndarray:
        """RMS tracking error of each component [rad]."""
        return np.sqrt(np.mean(self.errors ** 2, axis=0))

    @property
    def max_error(self) -> float:
        """Largest absolute error component [rad]."""
        return float(np.max(np.abs(self.errors)))

    @property
    def peak_torque(self) -> float:
        """Largest absolute commanded torque [N·m]."""
        return float(np.max(np.abs(self.tau)))

    @property
    def saturation_ratio(self) -> float:
        """Fraction of control periods with at least one saturated joint."""
        return float(np.mean(self.saturated))

    @property
    def stable(self) -> bool:
        """Finite everywhere and the error bounded by :attr:`bound`."""
        finite = all(np.all(np.isfinite(a)) for a in (self.q, self.tau, self.errors))
        return finite and self.max_error < self.bound


def simulate(law: ControlLaw, duration_s: float = 4.0, rate_hz: float = 1000.0,
             q_start: Sequence[float] | None = None, bound: float = 1.0) -> ClosedLoopResult:
    """Run ``law`` on its robot's plant for ``duration_s`` [s] at ``rate_hz`` [Hz].

    The plant starts at rest at ``q_start`` [rad], by default on the reference
    (``q_d(0)``, joint tracking). ``rate_hz`` must divide the plant's step rate.
    """
    robot = law.robot
    steps = robot.timestep_s * rate_hz
    if rate_hz <= 0 or abs(1.0 / steps - round(1.0 / steps)) > 1e-9:
        raise ControlError(f"closed loop: rate_hz = {rate_hz!r} must divide the plant "
                           f"rate {1.0 / robot.timestep_s:g} Hz")
    per_period = round(1.0 / steps)
    physics = RobotPhysics(robot)
    task = law.task_function
    start = task.reference(0.0).pos if q_start is None else np.asarray(q_start, float)
    physics.set_state(start)
    law.reset()
    count = int(round(duration_s * rate_hz))
    record = {key: [] for key in ("t", "q", "qd", "e", "tau", "sat")}
    for k in range(count):
        t = k / rate_hz
        q, qdot = physics.read("q"), physics.read("qdot")
        reference = task.reference(t)
        out = law.command(t, q, qdot, reference)
        physics.write("tau", out.tau)
        physics.step(per_period)
        for key, value in zip(record, (t, q, reference.pos, out.e, out.tau,
                                       bool(out.saturated.any()))):
            record[key].append(value)
        if not np.all(np.isfinite(q)):
            break
    return ClosedLoopResult(law.name, np.array(record["t"]), np.array(record["q"]),
                            np.array(record["qd"]), np.array(record["e"]),
                            np.array(record["tau"]), np.array(record["sat"]), bound)


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
    from orccad_app.control.spec import resolve
    from orccad_app.diagnostics import OrccadError
    from orccad_app.plugins import default_host

    args = _arguments(argv)
    try:
        host = default_host()
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
