r"""Reference trajectories: desired position, velocity and acceleration over time.

- :class:`Cosine` — RR-1801 eq. 9–10: :math:`q_d = q_0 (1 + \cos \omega t)`,
  :math:`\dot q_d = -q_0 \omega \sin \omega t` (the paper uses :math:`\omega = \pi`).
- :class:`MinimumJerk` — point to point in ``duration`` [s] with zero velocity and
  acceleration at both ends: :math:`s(\tau) = 10\tau^3 - 15\tau^4 + 6\tau^5`.
- :class:`Constant` — hold a position.

Time ``t_s`` [s] is measured from the start of the trajectory. Units follow the task
function: [rad] for joint tracking, [m] for Cartesian tracking. A trajectory whose start
is not given (``needs_start``) is completed with :meth:`Trajectory.with_start` from the
first measurement (the ``trajectory`` module's ``q`` input).

A type-1 update of a trajectory parameter keeps the set-point continuous (:mod:`.retuned`:
phase continuity, then a C² blend over ``BLEND_S``).

One module per family: :mod:`.base` (the interface), :mod:`.cosine`, :mod:`.minimum_jerk`,
:mod:`.constant`, :mod:`.retuned` (a trajectory retuned while it runs); their kinds (names, parameters) are in :mod:`orccad_app.control.catalogue`.
"""

from orccad_app.control.trajectories.base import Sample, Trajectory
from orccad_app.control.trajectories.constant import Constant
from orccad_app.control.trajectories.cosine import Cosine
from orccad_app.control.trajectories.minimum_jerk import MinimumJerk
from orccad_app.control.trajectories.retuned import BLEND_S, Retuned, retune

__all__ = ["Sample", "Trajectory", "Cosine", "MinimumJerk", "Constant", "Retuned", "retune",
           "BLEND_S"]
