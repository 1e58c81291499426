"""Control-code benchmark: µs per ``law.command`` and per ``trajectory.sample`` call.

For the 3-DOF arm (``arm3dof``) with joint tracking, it times, as the ``control_law`` and
``trajectory`` modules call them, the PID law (``kp``, ``kv``, ``ki`` and anti-windup, as in
missions/arm_pid.orc), computed torque with the Pinocchio model, and the ``cosine``,
``min_jerk`` and ``constant`` trajectories. Each is compared, in the same command, with a
hand-written numpy baseline doing the same arithmetic inline (PID with clipping and
conditional integration; computed torque with Pinocchio's ``crba``/``nonLinearEffects``;
the trajectory formulas) and the script checks both compute the same torques / samples.
Targets: PID ≤ 5 µs (issue 14), computed torque ≤ 8 µs per call (issue 27); trajectories likewise
(≤ 5 µs). Each figure is the best of ``--repeat`` runs of ``--calls`` calls.

    python bench/bench_control.py [--calls 20000] [--repeat 5] [--clock wall|cpu]

Exit status 0 when every target is met, 1 otherwise (2 is bad input, as for orccad).

Needs: no extra: ORCCAD's own dependencies.
"""

from __future__ import annotations

import argparse
import math
import time
from collections.abc import Callable

import numpy as np
import pinocchio

from orccad_app.control.spec import resolve
from orccad_app.plugin_host.host import PluginHost

Q0 = [0.5, 0.5, 0.5]
CLOCK = time.perf_counter
"""The clock of the timings (``--clock cpu``: ``time.process_time``)."""
TARGETS_US = {"pid": 5.0, "computed_torque": 8.0, "cosine": 5.0, "min_jerk": 5.0,
              "constant": 5.0}


def _states(calls: int) -> list[tuple[float, np.ndarray, np.ndarray]]:
    """Deterministic joint states (t [s], q [rad], qdot [rad/s]) along a cosine motion."""
    rng = np.random.default_rng(0)
    states = []
    for k in range(calls):
        t = k * 1e-3
        q = np.array(Q0) * (1.0 + math.cos(math.pi * t)) + rng.normal(0.0, 0.05, 3)
        qdot = -np.array(Q0) * math.pi * math.sin(math.pi * t) + rng.normal(0.0, 0.5, 3)
        states.append((t, q, qdot))
    return states


def _best_us(run: Callable[[], None], calls: int, repeat: int) -> float:
    best = math.inf
    for _ in range(repeat):
        start = CLOCK()
        run()
        best = min(best, CLOCK() - start)
    return best / calls * 1e6


def _law(host: PluginHost, call: tuple) -> tuple:
    robot = host.robot_types.get("arm3dof")
    task_spec = resolve(host, "task function", ("joint_tracking", {
        "trajectory": ("cosine", {"q0": Q0, "omega": math.pi})}))
    task_function = task_spec.build(robot)
    law = resolve(host, "control law", call).build(robot, task_function)
    return robot, task_function, law


def bench_law(host: PluginHost, call: tuple, baseline_factory: Callable,
              states: list, repeat: int) -> tuple[float, float]:
    """(µs per law.command, µs per baseline call); checks both give the same torques."""
    robot, task_function, law = _law(host, call)
    references = [task_function.reference(t) for t, _, _ in states]
    pairs = list(zip(states, references))

    def run_law() -> list:
        law.reset()
        return [law.command(t, q, qdot, ref).tau for (t, q, qdot), ref in pairs]

    baseline = baseline_factory(robot, law)

    def run_baseline() -> list:
        baseline.reset()
        return [baseline(t, q, qdot, ref.pos, ref.vel, ref.acc) for (t, q, qdot), ref in pairs]

    ours, theirs = run_law(), run_baseline()
    worst = max(float(np.max(np.abs(a - b))) for a, b in zip(ours, theirs))
    assert worst <= 1e-9, f"{call[0]}: law and baseline differ by {worst} N·m"
    return (_best_us(run_law, len(pairs), repeat), _best_us(run_baseline, len(pairs), repeat))


def _bounds(c, qdot):
    """The torque–speed bounds max(τmin, -α - βq̇) ≤ τ ≤ min(τmax, α - βq̇), inline."""
    back_emf = c.beta * qdot
    return np.maximum(c.tau_min, -c.alpha - back_emf), np.minimum(c.tau_max, c.alpha - back_emf)


class NumpyPID:
    """The baseline PID: e = q - qd, tau = clip(-(kp e + kv ė + ki ∫e)), conditional
    integration of the saturated joints (the law's anti-windup for diagonal gains)."""

    def __init__(self, robot, law):
        self.kp, self.kv, self.ki = (np.diag(g).copy() for g in
                                     (law.gains.kp, law.gains.kv, law.gains.ki))
        self.constraint = robot.actuator_constraint

    def reset(self) -> None:
        self.integral = np.zeros(3)
        self.t_prev = None
        self.sat_dir = np.zeros(3)

    def __call__(self, t, q, qdot, qd, qd_dot, qd_ddot):
        e = q - qd
        dt = 0.0 if self.t_prev is None else max(t - self.t_prev, 0.0)
        self.t_prev = t
        delta = e * dt
        push = (-self.ki * delta * self.sat_dir) > 0
        self.integral = self.integral + np.where(push, 0.0, delta)
        tau_unsat = -(self.kp * e + self.kv * (qdot - qd_dot) + self.ki * self.integral)
        tau = np.clip(tau_unsat, *_bounds(self.constraint, qdot))
        self.sat_dir = np.sign(tau_unsat - tau)
        return tau


class NumpyComputedTorque:
    """The baseline computed torque: M(q)(q̈d - kp e - kv ė) + N(q, q̇) + D q̇, clipped."""

    def __init__(self, robot, law):
        self.kp, self.kv = np.diag(law.gains.kp).copy(), np.diag(law.gains.kv).copy()
        self.model = law.model.model
        self.data = self.model.createData()
        self.damping = np.array(self.model.damping, dtype=float)
        self.constraint = robot.actuator_constraint

    def reset(self) -> None:
        pass

    def __call__(self, t, q, qdot, qd, qd_dot, qd_ddot):
        upper = pinocchio.crba(self.model, self.data, q)
        mass = np.triu(upper) + np.triu(upper, 1).T
        bias = pinocchio.nonLinearEffects(self.model, self.data, q, qdot)
        acc = qd_ddot - self.kp * (q - qd) - self.kv * (qdot - qd_dot)
        return np.clip(mass @ acc + bias + self.damping * qdot, *_bounds(self.constraint, qdot))


def _trajectory_baselines() -> dict[str, tuple[tuple, Callable[[float], tuple]]]:
    q0 = np.array(Q0)
    goal, start, duration = np.array([0.2, -0.3, 0.4]), np.array(Q0), 2.0

    def cosine(t):
        c, s = math.cos(math.pi * t), math.sin(math.pi * t)
        return q0 * (1.0 + c), -q0 * math.pi * s, -q0 * math.pi ** 2 * c

    def min_jerk(t):
        x = min(max(t / duration, 0.0), 1.0)
        delta = goal - start
        return (start + x ** 3 * (10.0 - 15.0 * x + 6.0 * x ** 2) * delta,
                30.0 * x ** 2 * (1.0 - x) ** 2 / duration * delta,
                60.0 * x * (1.0 - x) * (1.0 - 2.0 * x) / duration ** 2 * delta)

    def constant(t):
        return q0, np.zeros(3), np.zeros(3)

    return {"cosine": (("cosine", {"q0": Q0, "omega": math.pi}), cosine),
            "min_jerk": (("min_jerk", {"goal": goal.tolist(), "duration": duration,
                                       "start": Q0}), min_jerk),
            "constant": (("constant", {"value": Q0}), constant)}


def bench_trajectory(host: PluginHost, call: tuple, baseline: Callable, calls: int,
                     repeat: int) -> tuple[float, float]:
    """(µs per trajectory.sample, µs per baseline call); checks both agree."""
    trajectory = resolve(host, "trajectory", call).build()
    times = [k * 1e-3 for k in range(calls)]
    for t in times[:: max(1, calls // 200)]:
        sample, expected = trajectory.sample(t), baseline(t)
        for got, want in zip((sample.pos, sample.vel, sample.acc), expected):
            assert np.allclose(got, want, rtol=1e-12, atol=1e-12), (call[0], t, got, want)

    def run_ours() -> None:
        for t in times:
            trajectory.sample(t)

    def run_baseline() -> None:
        for t in times:
            baseline(t)

    return _best_us(run_ours, calls, repeat), _best_us(run_baseline, calls, repeat)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--calls", type=int, default=20000, help="calls per run")
    parser.add_argument("--repeat", type=int, default=5, help="runs per figure (best kept)")
    parser.add_argument("--clock", choices=("wall", "cpu"), default="wall",
                        help="wall clock (default) or the process's CPU time (a loaded "
                             "machine: what a call costs, not the processor share it got)")
    args = parser.parse_args()
    global CLOCK
    if args.clock == "cpu":
        CLOCK = time.process_time
    host = PluginHost.load()
    states = _states(args.calls)
    rows = [("pid", *bench_law(host, ("pid", {"kp": 400.0, "kv": 40.0, "ki": 10.0}),
                               NumpyPID, states, args.repeat)),
            ("computed_torque", *bench_law(host, ("computed_torque", {"kp": 400.0, "kv": 40.0}),
                                           NumpyComputedTorque, states, args.repeat))]
    for name, (call, baseline) in _trajectory_baselines().items():
        rows.append((name, *bench_trajectory(host, call, baseline, args.calls, args.repeat)))
    print(f"arm3dof, {args.calls} calls, best of {args.repeat}")
    print(f"  {'component':<16} {'ORCCAD µs':>10} {'numpy µs':>9} {'ratio':>6} {'target':>7}")
    met = True
    for name, ours, theirs in rows:
        ok = ours <= TARGETS_US[name]
        met = met and ok
        print(f"  {name:<16} {ours:10.2f} {theirs:9.2f} {ours / theirs:6.2f} "
              f"{'<= ' + format(TARGETS_US[name], 'g'):>7} {'met' if ok else 'MISSED'}")
    return 0 if met else 1


if __name__ == "__main__":
    raise SystemExit(main())
