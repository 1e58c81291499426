r"""The lean path of :meth:`ControlLaw.command`: joint tracking, diagonal gains.

Most laws of a mission are joint tracking (:math:`\hat J = I`) with diagonal gains, an
identity or Pinocchio model. For them :class:`LeanPath` evaluates eq. 5 without building a
:class:`~orccad_app.control.task_functions.TaskState`, without the identity products, without
the constraint's argument checks and with preallocated work arrays. For the identity model
(PID) it performs the same floating-point operations as the general path, so the torques are
bit-identical:

- a diagonal matrix times a vector, ``K @ x``, is ``diag(K) * x`` (the off-diagonal terms
  add exact zeros; a matrix product never returns :math:`-0`, and every consumer below
  either adds a zero or is itself a matrix product, so the sign of a zero never shows);
- :math:`\hat M = I` turns :math:`-\hat M \hat J^{-1} F + \hat N` into ``0 - F``.

**Computed torque in one Pinocchio call.** With the Pinocchio model,
:math:`-\hat M F + \hat N - \hat M \hat f` with :math:`\hat f = -\ddot q_d` is
:math:`\hat M (\ddot q_d - F) + \hat N`, which is what the recursive Newton-Euler algorithm
computes: ``rnea(q, q̇, a)`` :math:`= M(q) a + C(q, \dot q) \dot q + g(q)` with
:math:`a = \ddot q_d - F` (the viscous damping :math:`D \dot q` added after). The general path
computes the same quantity as ``crba`` (the mass matrix), two matrix products and
``nonLinearEffects``; the two agree to rounding (a few units in the last place: relative
differences of order 1e-15, ``tests/control/test_lean_path.py``), one ``rnea`` costing about
a third of the three calls.

Any other law (full gains, Cartesian tracking, a perturbed model with an integral, velocity-
dependent bounds) or an input of the wrong shape goes through the general path.

**Small robots, plain floats.** For at most :data:`SCALAR_DOF` joints with constant or
all-velocity-dependent bounds, :meth:`LeanPath.command` works on Python floats
(``ndarray.tolist()``) instead of numpy arrays: for three joints numpy's per-call overhead is
most of the cost (computed torque hands its acceleration to ``rnea`` as an array). The
operations are IEEE-754 double operations in the same order as the numpy ones, with numpy's tie rules: ``np.maximum(a, b)`` and
``np.minimum(a, b)`` return ``b`` when ``a == b`` (they differ only in the sign of a zero),
``np.sign`` returns ``+0.0`` for both zeros. Inputs with a NaN or an infinity, or an
unsaturated torque that is not finite, take the numpy lean path from the same state (NaN
propagation differs between Python's comparisons and numpy's). The torques are
therefore bit-identical to the numpy lean path (``tests/control/test_lean_path.py`` compares
both paths).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np

from orccad_app.control.constraints import ActuatorConstraint
from orccad_app.control.models import IdentityModel, PinocchioModel
from orccad_app.control.task_functions.joint import JointTracking
from orccad_app.control.laws.output import LawOutput
from orccad_app.control.trajectories import Sample

if TYPE_CHECKING:  # the law object, duck-typed: base imports this module
    ControlLaw = Any

__all__ = ["LeanPath", "lean_path", "SCALAR_DOF"]

SCALAR_DOF = 8
"""Largest number of joints served by the plain-float PID path."""
_isfinite = math.isfinite
_array = np.array
_SETTERS = tuple(LawOutput.__dict__[name].__set__ for name in ("tau", "tau_unsat",
                                                                "saturated", "e"))


def _law_output(tau: np.ndarray, tau_unsat: np.ndarray, saturated: np.ndarray,
                e: np.ndarray) -> LawOutput:
    """``LawOutput(tau, tau_unsat, saturated, e)`` through its slots' descriptors: the
    frozen dataclass's ``__init__`` (``object.__setattr__`` per field) costs twice as much."""
    out = object.__new__(LawOutput)
    set_tau, set_unsat, set_saturated, set_e = _SETTERS
    set_tau(out, tau)
    set_unsat(out, tau_unsat)
    set_saturated(out, saturated)
    set_e(out, e)
    return out


def _diagonal(matrix: np.ndarray) -> np.ndarray | None:
    """The diagonal of ``matrix`` if every other entry is zero, else ``None``."""
    diagonal = np.diag(matrix).copy()
    if np.count_nonzero(matrix - np.diag(diagonal)) or not np.all(np.isfinite(matrix)):
        return None
    return diagonal


def lean_path(law: ControlLaw) -> LeanPath | None:
    """The lean path of ``law``, or ``None`` when it must use the general path."""
    if type(law.task_function) is not JointTracking:
        return None
    if type(law.constraint) is not ActuatorConstraint:
        return None
    model = law.model
    identity = type(model) is IdentityModel
    if not identity and type(model) is not PinocchioModel:
        return None
    gains = [_diagonal(g) for g in (law.gains.kp, law.gains.kv, law.gains.ki)]
    if any(g is None for g in gains):
        return None
    ki_any = bool(np.any(law.gains.ki))
    if identity and law.feedforward or not identity and ki_any:
        return None
    return LeanPath(law, *gains, ki_any=ki_any, identity=identity)


class LeanPath:
    """Precomputed gains, bounds and work arrays of one law (see the module docstring)."""

    def __init__(self, law: ControlLaw, kp: np.ndarray, kv: np.ndarray, ki: np.ndarray,
                 ki_any: bool, identity: bool):
        dof = law.robot.dof
        self.kp, self.kv, self.ki = kp, kv, ki
        self.neg_ki = -ki
        self.ki_any = ki_any
        self.anti_windup = bool(law.params.get("anti_windup", True))
        self.identity = identity
        self.feedforward = law.feedforward
        self.shape = (dof,)
        constraint = law.constraint
        self.constraint = constraint
        self.tau_min, self.tau_max = constraint.tau_min, constraint.tau_max
        self.alpha, self.neg_alpha, self.beta = constraint.alpha, -constraint.alpha, constraint.beta
        #: bounds: constant (β = 0), per call from β q̇ (β > 0), else the constraint's own
        self.beta_mode = ("zero" if not np.any(constraint.beta) else
                          "full" if np.all(constraint.beta != 0.0) else "mixed")
        self.low, self.high = constraint.bounds(np.zeros(dof))
        self.zeros = np.zeros(dof)
        self.work = np.empty(dof)
        self.work2 = np.empty(dof)
        if not identity:
            self.pin, self.pin_model = law.model._pin, law.model.model
            self.pin_data, self.damping = law.model.data, law.model.damping
        self.scalar = (dof <= SCALAR_DOF and self.beta_mode != "mixed"
                       and law.task_function.dim == dof)
        if self.scalar:  # the constants of the plain-float path, as lists of floats
            self.lists = tuple(np.asarray(a, dtype=float).tolist() for a in (
                kp, kv, ki, self.neg_ki, self.tau_min, self.tau_max, self.alpha,
                self.neg_alpha, self.beta, self.low, self.high))
            if not identity:
                self.damping_list = np.asarray(self.damping, dtype=float).tolist()

    def command(self, law: ControlLaw, t_s: float, q: Any, qdot: Any,
                reference: Sample) -> LawOutput | None:
        """:meth:`ControlLaw.command` for this law (same operations, same results);
        ``None`` for inputs of another shape (the general path then reports them)."""

        q = np.asarray(q, dtype=float)
        qdot = np.asarray(qdot, dtype=float)
        if q.shape != self.shape or qdot.shape != self.shape:
            return None
        if self.scalar:
            out = self._scalar_command(law, t_s, q, qdot, reference)
            if out is not None:
                return out
        e = q - reference.pos
        e_dot = qdot - reference.vel
        self._integrate(law, e, t_s)
        feedback = self.kp * e
        feedback += np.multiply(self.kv, e_dot, out=self.work)
        if self.ki_any:
            feedback += np.multiply(self.ki, law.integral, out=self.work)
        if self.identity:
            tau_unsat = np.subtract(0.0, feedback)
        else:
            tau_unsat = self._model_torque(q, qdot, feedback, reference)
        low, high = self._bounds(qdot)
        tau = np.minimum(np.maximum(tau_unsat, low), high)
        law._sat_dir = np.sign(tau_unsat - tau)
        return LawOutput(tau=tau, tau_unsat=tau_unsat, saturated=tau != tau_unsat, e=e)

    def _model_torque(self, q: np.ndarray, qdot: np.ndarray, feedback: np.ndarray,
                      reference: Sample) -> np.ndarray:
        """:math:`\\hat M (\\ddot q_d - F) + \\hat N` in one recursive Newton-Euler pass
        (``rnea(q, q̇, a)`` is :math:`M(q) a + C(q, q̇) q̇ + g(q)` exactly), plus the
        damping; without feed-forward :math:`a = -F`."""
        if self.feedforward:
            acc = np.subtract(reference.acc, feedback, out=self.work2)
        else:
            acc = np.subtract(0.0, feedback, out=self.work2)
        torque = self.pin.rnea(self.pin_model, self.pin_data, q, qdot, acc)
        return np.add(torque, np.multiply(self.damping, qdot, out=self.work))

    def _bounds(self, qdot: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`ActuatorConstraint.bounds` (same operations)."""
        if self.beta_mode == "zero":
            return self.low, self.high
        if self.beta_mode == "mixed":
            return self.constraint.bounds(qdot)
        back_emf = self.beta * qdot
        low = np.maximum(self.tau_min, np.subtract(self.neg_alpha, back_emf))
        high = np.minimum(self.tau_max, np.subtract(self.alpha, back_emf, out=back_emf))
        high = np.maximum(high, np.minimum(low, self.tau_max))
        return np.minimum(low, high, out=low), high

    def _integrate(self, law: ControlLaw, e: np.ndarray, t_s: float) -> None:
        t_prev = law._t_prev
        dt = 0.0 if t_prev is None else max(t_s - t_prev, 0.0)
        law._t_prev = t_s
        if dt == 0.0 or not self.ki_any:
            return
        delta = e * dt
        sat_dir = law._sat_dir
        if self.anti_windup and np.count_nonzero(sat_dir):
            push = self.neg_ki * delta * sat_dir > 0
            delta[push] = 0.0
        law.integral = law.integral + delta

    def _scalar_command(self, law: ControlLaw, t_s: float, q: np.ndarray, qdot: np.ndarray,
                        reference: Sample) -> LawOutput | None:
        """The law on Python floats (see the module docstring); ``None`` for non-finite
        inputs or torques, or a reference of another shape or type (the numpy path then
        runs, from the same state)."""
        pos, vel = reference.pos, reference.vel
        shape = self.shape
        if pos.shape != shape or vel.shape != shape or pos.dtype != np.float64 \
                or vel.dtype != np.float64:
            return None
        ql, qdl, pl, vl = q.tolist(), qdot.tolist(), pos.tolist(), vel.tolist()
        if not _isfinite(sum(ql) + sum(qdl) + sum(pl) + sum(vl)):
            return None
        t_prev = law._t_prev
        law._t_prev = t_s
        if self.identity:
            integral, e, tau_unsat = self._pid(law, t_s, t_prev, ql, qdl, pl, vl)
        else:
            integral = None  # no integral on this path (see lean_path)
            e, tau_unsat = self._model(q, qdot, ql, qdl, pl, vl, reference)
        if not _isfinite(sum(tau_unsat)):
            law._t_prev = t_prev
            return None
        return self._clamp(law, tau_unsat, e, qdl, integral)

    def _pid(self, law: ControlLaw, t_s: float, t_prev: float | None, ql: list, qdl: list,
             pl: list, vl: list) -> tuple[list | None, list, list]:
        """(the new integral or ``None`` if unchanged, e, the unsaturated torque)."""
        kp, kv, ki, neg_ki = self.lists[:4]
        dt = 0.0 if t_prev is None else max(t_s - t_prev, 0.0)
        ki_any = self.ki_any
        integrate = dt != 0.0 and ki_any
        integral = law._integral_list
        integral = law.integral.tolist() if integral is None else integral[:]
        sat_dir = law._sat_list
        if sat_dir is None:
            sat_dir = law._sat_dir.tolist()
        windup = integrate and self.anti_windup and any(sat_dir)
        e, tau_unsat = [], []
        for j in range(len(ql)):  # one joint: the numpy lean path's operations, in order
            x = ql[j] - pl[j]
            e.append(x)
            if integrate:
                d = x * dt
                if windup and neg_ki[j] * d * sat_dir[j] > 0:
                    d = 0.0
                integral[j] = integral[j] + d
            u = kp[j] * x + kv[j] * (qdl[j] - vl[j])
            if ki_any:
                u = u + ki[j] * integral[j]
            tau_unsat.append(0.0 - u)
        return (integral if integrate else None), e, tau_unsat

    def _model(self, q: np.ndarray, qdot: np.ndarray, ql: list, qdl: list, pl: list,
               vl: list, reference: Sample) -> tuple[list, list]:
        """(e, the unsaturated torque) of computed torque: the commanded acceleration
        :math:`a = \\ddot q_d - F` on floats, then one ``rnea`` (:math:`M a + N`) and the
        damping (see :meth:`_model_torque`)."""
        kp, kv = self.lists[:2]
        e = [a - b for a, b in zip(ql, pl)]
        feedback = [p * x + v * (w - r) for p, x, v, w, r in zip(kp, e, kv, qdl, vl)]
        if self.feedforward:
            acc = _array([d - f for d, f in zip(reference.acc.tolist(), feedback)])
        else:
            acc = _array([0.0 - f for f in feedback])
        torque = self.pin.rnea(self.pin_model, self.pin_data, q, qdot, acc).tolist()
        return e, [t + d * w for t, d, w in zip(torque, self.damping_list, qdl)]

    def _clamp(self, law: ControlLaw, tau_unsat: list, e: list, qdl: list,
               integral: list | None) -> LawOutput:
        """The actuator constraint on floats (:meth:`_bounds` and the clamp, numpy's tie
        rules), the saturation directions, the law's state written back."""
        tau_min, tau_max, alpha, neg_alpha, beta, low, high = self.lists[4:]
        full = self.beta_mode == "full"
        tau, saturated, sat_dir = [], [], []
        lo = hi = 0.0
        for j in range(len(tau_unsat)):
            u = tau_unsat[j]
            if full:  # numpy's maximum/minimum return the second operand on a tie
                back_emf = beta[j] * qdl[j]
                t_hi = tau_max[j]
                lo = neg_alpha[j] - back_emf
                if tau_min[j] > lo:
                    lo = tau_min[j]                  # np.maximum(tau_min, lo)
                hi = alpha[j] - back_emf
                if t_hi < hi:
                    hi = t_hi                        # np.minimum(tau_max, hi)
                floor = lo if lo < t_hi else t_hi    # np.minimum(lo, tau_max)
                if not hi > floor:
                    hi = floor                       # np.maximum(hi, floor)
                if not lo < hi:
                    lo = hi                          # np.minimum(lo, hi)
            else:
                lo, hi = low[j], high[j]
            v = u if u > lo else lo                  # np.maximum(tau_unsat, low)
            if not v < hi:
                v = hi                               # np.minimum(., high)
            tau.append(v)
            d = u - v
            sat_dir.append(1.0 if d > 0 else -1.0 if d < 0 else 0.0)  # np.sign
            saturated.append(v != u)
        if integral is not None:  # kept as floats: ControlLaw.integral makes the array
            law._integral_list = integral
        law._sat_list = sat_dir
        return _law_output(_array(tau), _array(tau_unsat), _array(saturated), _array(e))
