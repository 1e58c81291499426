r"""Task functions :math:`e(q, t)` to regulate to zero (RR-1801 §3.1.2).

A task function evaluates, at :math:`(q, \dot q)` and the reference sample
:math:`(x_d, \dot x_d, \ddot x_d)` of its trajectory, everything eq. 5 needs
(:class:`TaskState`): :math:`e`, :math:`\dot e = J \dot q + \partial e/\partial t`, the
task Jacobian :math:`J = \partial e/\partial q` and a model of its inverse, and
:math:`f` such that :math:`\ddot e = J \ddot q + f` (eq. 3).

- :class:`JointTracking` — :math:`e = q - q_d(t)`, :math:`J = I`, :math:`f = -\ddot q_d`
  (eq. 6–7).
- :class:`CartesianTracking` — :math:`e = p(q) - p_d(t)` for the position of a frame
  (the end effector), :math:`J` its translational Jacobian (Pinocchio, world-aligned),
  :math:`f = \dot J \dot q - \ddot p_d`, and the damped-least-squares inverse
  :math:`J^+ = J^T (J J^T + \lambda^2 I)^{-1}` that stays bounded near singularities.

One module per family: :mod:`.base` (the interface), :mod:`.joint`, :mod:`.cartesian`; their
kinds (names, parameters) are in :mod:`orccad_app.control.catalogue`.
"""

from orccad_app.control.task_functions.base import TaskFunction, TaskState
from orccad_app.control.task_functions.cartesian import CartesianTracking
from orccad_app.control.task_functions.joint import JointTracking

__all__ = ["TaskState", "TaskFunction", "JointTracking", "CartesianTracking"]
