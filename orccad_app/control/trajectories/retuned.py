r"""A trajectory retuned while it runs (a type-1 update of one of its parameters).

Rebuilding a trajectory with a parameter changed and sampling it at the same time makes the
set-point jump: retuning the cosine's ``omega`` at :math:`t_u` moves :math:`q_0(1 + \cos\omega
t_u)` to :math:`q_0(1 + \cos\omega' t_u)` in one period. A retuned trajectory instead keeps
the set-point continuous, in two steps:

1. **phase continuity** — a trajectory whose kind has a phase (``cosine``) is sampled with a
   time shift that gives it, at :math:`t_u`, the phase the previous one had
   (:meth:`Trajectory.continuing`): retuning ``omega`` changes the frequency from the current
   phase on, the position does not move;
2. **a C² blend of what is left** — the difference of position, velocity and acceleration
   between the previous set-point and the new trajectory at :math:`t_u` (a new amplitude, goal,
   duration or value; the velocity of a new ``omega``) decays to zero over ``BLEND_S`` along the
   quintic that starts with that difference and ends with zero position, velocity and
   acceleration. The set-point and its first two derivatives are continuous; after
   :math:`t_u` + ``BLEND_S`` the set-point is the new trajectory's.
"""

from __future__ import annotations

import numpy as np

from orccad_app.control.trajectories.base import Sample, Trajectory

__all__ = ["Retuned", "retune", "BLEND_S"]

BLEND_S = 0.25
"""Duration of the blend from the previous set-point onto the retuned trajectory [s]."""


def _hermite(tau: float) -> tuple[tuple[float, float, float], ...]:
    """The quintic basis at ``tau`` in [0, 1]: for each of the three start conditions
    (position, velocity·T, acceleration·T²) its value and first two derivatives in ``tau``."""
    t2, t3, t4, t5 = tau * tau, tau ** 3, tau ** 4, tau ** 5
    h0 = (1 - 10 * t3 + 15 * t4 - 6 * t5, -30 * t2 + 60 * t3 - 30 * t4,
          -60 * tau + 180 * t2 - 120 * t3)
    h1 = (tau - 6 * t3 + 8 * t4 - 3 * t5, 1 - 18 * t2 + 32 * t3 - 15 * t4,
          -36 * tau + 96 * t2 - 60 * t3)
    h2 = ((t2 - 3 * t3 + 3 * t4 - t5) / 2, (2 * tau - 9 * t2 + 12 * t3 - 5 * t4) / 2,
          (2 - 18 * tau + 36 * t2 - 20 * t3) / 2)
    return h0, h1, h2


class Retuned(Trajectory):
    """``base`` sampled at ``t + shift_s``, plus the decaying blend of ``gap`` from ``at_s``.

    :param base: the rebuilt trajectory (the new parameters).
    :param at_s: when it was retuned [s] (task time).
    :param shift_s: the time shift giving it the previous phase [s].
    :param gap: previous set-point minus ``base`` at ``at_s`` (position, velocity, acceleration).
    :param blend_s: how long the gap takes to vanish [s].
    """

    def __init__(self, base: Trajectory, at_s: float, shift_s: float, gap: Sample,
                 blend_s: float = BLEND_S) -> None:
        self.base = base
        self.at_s = float(at_s)
        self.shift_s = float(shift_s)
        self.gap = gap
        self.blend_s = float(blend_s)
        self.name = base.name
        self.origin = base.origin
        self.needs_start = False
        base_end = base.end_time_s
        self.end_time_s = None if base_end is None else \
            max(base_end - self.shift_s, self.at_s + self.blend_s)

    @property
    def dim(self) -> int:
        return self.base.dim

    def final(self) -> np.ndarray | None:
        return self.base.final()

    def phase_time_s(self, t_s: float) -> float:
        """The time at which the base trajectory is sampled for task time ``t_s`` [s]."""
        return t_s + self.shift_s

    def sample(self, t_s: float) -> Sample:
        sample = self.base.sample(t_s + self.shift_s)
        elapsed = t_s - self.at_s
        if elapsed >= self.blend_s:
            return sample
        period = self.blend_s
        tau = max(elapsed, 0.0) / period
        (p0, p1, p2), (v0, v1, v2), (a0, a1, a2) = _hermite(tau)
        gap = self.gap
        pos = p0 * gap.pos + v0 * period * gap.vel + a0 * period ** 2 * gap.acc
        vel = (p1 * gap.pos + v1 * period * gap.vel + a1 * period ** 2 * gap.acc) / period
        acc = (p2 * gap.pos + v2 * period * gap.vel + a2 * period ** 2 * gap.acc) / period ** 2
        return Sample(pos=sample.pos + pos, vel=sample.vel + vel, acc=sample.acc + acc)


def retune(previous: Trajectory, rebuilt: Trajectory, at_s: float) -> Trajectory:
    """``rebuilt`` continuing ``previous`` from task time ``at_s`` [s] (module docstring)."""
    if rebuilt.needs_start:
        return rebuilt
    before = previous.sample(at_s)
    prior, prior_t_s = previous, at_s
    if isinstance(previous, Retuned):
        prior, prior_t_s = previous.base, previous.phase_time_s(at_s)
    shift_s = rebuilt.continuing(prior, prior_t_s, at_s)
    after = rebuilt.sample(at_s + shift_s)
    gap = Sample(pos=np.asarray(before.pos, float) - after.pos,
                 vel=np.asarray(before.vel, float) - after.vel,
                 acc=np.asarray(before.acc, float) - after.acc)
    return Retuned(rebuilt, at_s, shift_s, gap)
