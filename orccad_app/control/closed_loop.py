"""Closed-loop check of a control law on a robot's MuJoCo plant, without the executive.

The law runs at ``rate_hz`` with a zero-order hold on the torque; the plant integrates at
the MJCF timestep (1 ms for ``arm3dof``). This is the continuous-time design check of
RR-1801 §3.1 before the time-constrained specification: no processors, no delays.

Reproduce the figures of ``docs/control.md``::

    python -m orccad_app.commands.closed_loop            # PID vs computed torque, 4 s, 1 kHz
    python -m orccad_app.commands.closed_loop --kp 400 --kv 40 --ki 10 --duration 4
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from orccad_app.control.errors import ControlError
from orccad_app.control.laws.base import ControlLaw
from orccad_app.control.physics import RobotPhysics

__all__ = ["ClosedLoopResult", "simulate"]


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
