r"""Computed torque split into Module-Tasks at different rates (RR-1801 §6.2).

RR-1801 §6.2 asks which parts of a control law must run at every sample: the *feedback* path
is critical, the dynamic model and the feed-forward less so. These two module kinds cut the
joint-space computed torque

.. math::

    \Gamma = \hat M(q)\,u + \hat N(q, \dot q), \qquad
    u = \ddot q_d - K_p e - K_v \dot e, \qquad e = q - q_d, \quad \dot e = \dot q - \dot q_d

into Module-Tasks connected by ports, so that each can have its own period, execution time,
processor and protocol:

``dynamic_model`` (default 10 ms period, 0.5 ms WCET)
    in ``q`` [rad], ``qdot`` [rad/s]; out ``M`` (:math:`\hat M(q)` [kg·m²], the ``n × n``
    matrix row by row as a vector of ``n²``) and ``N`` (:math:`\hat N(q, \dot q)` [N·m]:
    gravity, Coriolis, centrifugal and viscous damping), from Pinocchio on the robot's MJCF
    (``model = "pinocchio"``), a ``perturbed`` copy, or ``identity``.
``ct_feedback`` (default 1 ms period, 0.2 ms WCET)
    in ``qd``, ``qd_dot``, ``qd_ddot`` (the reference), ``q``, ``qdot`` and the model's ``M``,
    ``N``; out ``tau`` [N·m] (after the robot's actuator constraint), ``e`` [rad] and
    ``saturated``. It applies :math:`\Gamma = \hat M u + \hat N` with the *latest* model it
    read: between two model updates :math:`\hat M` and :math:`\hat N` are those of the state
    the model Module-Task last read, which is what the model-update period costs. Until the
    first model arrives it writes nothing (a port never written reads "none yet"). Parameters
    ``kp`` [1/s²] and ``kv`` [1/s] (``adjust ctrl.kp = …`` updates them).

With both at 1 ms and zero execution times this is :class:`~orccad_app.control.laws.scheme.
ComputedTorque` delayed by one model period; ``bench/timing_table.py --multirate`` measures
the tracking error against the model period (docs/control.md).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from orccad_app.control.laws.base import build_model
from orccad_app.control.laws.gains import gain_matrix
from orccad_app.control.models import MODEL_NAMES
from orccad_app.control.module import ModuleContext, ModuleInstance, ModuleKind, PortSpec, Timing
from orccad_app.control.params import ParamSpec
from orccad_app.control.ports import TASK_ERROR

__all__ = ["DynamicModelModule", "ComputedTorqueFeedbackModule"]


def _vector(name: str, direction: str, doc: str) -> PortSpec:
    return PortSpec(name, direction, "vector", None, True, doc)


class DynamicModelModule(ModuleKind):
    """Computes :math:`\\hat M(q)` and :math:`\\hat N(q, \\dot q)` for ``ct_feedback``."""

    name = "dynamic_model"
    summary = "M̂(q) and N̂(q, q̇) of the robot (Pinocchio), for ct_feedback"
    ports = (_vector("q", "in", "joint positions [rad]"),
             _vector("qdot", "in", "joint velocities [rad/s]"),
             _vector("M", "out", "M̂(q) row by row, n² values [kg·m²]"),
             _vector("N", "out", "N̂(q, q̇) [N·m]"))
    params = (
        ParamSpec("model", "string", "pinocchio", "M̂, N̂ model", choices=MODEL_NAMES),
        ParamSpec("perturbation", "float", 0.1, "relative model error of 'perturbed' [-]", 0.0),
        ParamSpec("seed", "int", 0, "random seed of 'perturbed'"),
    )
    default_timing = Timing.from_ms(10.0, 0.5)

    def _instantiate(self, values: dict[str, Any], context: ModuleContext) -> ModuleInstance:
        return _DynamicModelInstance(self, values, context)


class _DynamicModelInstance(ModuleInstance):
    def __init__(self, kind: ModuleKind, values: dict[str, Any], context: ModuleContext):
        robot = context.require_robot(kind.name)
        dof = robot.dof
        ports = tuple(p.with_dim(dof * dof if p.name == "M" else dof) for p in kind.ports)
        super().__init__(kind, values, ports)
        self._robot = robot
        self.model = build_model(values["model"], robot, values["perturbation"], values["seed"])

    def _param_changed(self, name: str) -> None:
        p = self.params
        self.model = build_model(p["model"], self._robot, p["perturbation"], p["seed"])

    def compute(self, t_s: float, inputs: Mapping[str, Any]) -> dict[str, Any]:
        q, qdot = inputs.get("q"), inputs.get("qdot")
        if q is None or qdot is None:
            return {}
        q = np.asarray(q, dtype=float)
        qdot = np.asarray(qdot, dtype=float)
        return {"M": self.model.mass_matrix(q).reshape(-1),
                "N": np.asarray(self.model.nonlinear_effects(q, qdot), dtype=float)}


class ComputedTorqueFeedbackModule(ModuleKind):
    """The feedback path of a split computed torque: PD on the error, then M̂ u + N̂."""

    name = "ct_feedback"
    summary = "computed-torque feedback: τ = M̂ (q̈_d − kp e − kv ė) + N̂ with the latest M̂, N̂"
    ports = (_vector("qd", "in", "reference position [rad]"),
             _vector("qd_dot", "in", "reference velocity [rad/s]"),
             _vector("qd_ddot", "in", "reference acceleration [rad/s²]"),
             _vector("q", "in", "joint positions [rad]"),
             _vector("qdot", "in", "joint velocities [rad/s]"),
             _vector("M", "in", "M̂(q) row by row, from dynamic_model [kg·m²]"),
             _vector("N", "in", "N̂(q, q̇), from dynamic_model [N·m]"),
             _vector("tau", "out", "joint torques [N·m]"),
             _vector(TASK_ERROR, "out", "task error q − q_d [rad]"),
             PortSpec("saturated", "out", "bool", None, True, "a torque is at its bound"))
    params = (
        ParamSpec("kp", "float|vector", 400.0, "position gain [1/s²]", 0.0, True),
        ParamSpec("kv", "float|vector", 40.0, "velocity gain [1/s]", 0.0, True),
    )
    default_timing = Timing.from_ms(1.0, 0.2)

    def _instantiate(self, values: dict[str, Any], context: ModuleContext) -> ModuleInstance:
        return _FeedbackInstance(self, values, context)


class _FeedbackInstance(ModuleInstance):
    def __init__(self, kind: ModuleKind, values: dict[str, Any], context: ModuleContext):
        robot = context.require_robot(kind.name)
        self.dof = dof = robot.dof
        ports = tuple(p.with_dim(dof * dof if p.name == "M" else dof) for p in kind.ports)
        super().__init__(kind, values, ports)
        self.constraint = robot.actuator_constraint
        self._gains()

    def _gains(self) -> None:
        self.kp = gain_matrix(self.kind.name, "kp", self.params["kp"], self.dof)
        self.kv = gain_matrix(self.kind.name, "kv", self.params["kv"], self.dof)

    def _param_changed(self, name: str) -> None:
        self._gains()

    def compute(self, t_s: float, inputs: Mapping[str, Any]) -> dict[str, Any]:
        values = [inputs.get(p) for p in ("qd", "qd_dot", "qd_ddot", "q", "qdot", "M", "N")]
        if any(v is None for v in values):
            return {}
        qd, qd_dot, qd_ddot, q, qdot, mass, bias = (np.asarray(v, dtype=float) for v in values)
        e = q - qd
        u = qd_ddot - self.kp @ e - self.kv @ (qdot - qd_dot)
        tau_unsat = mass.reshape(self.dof, self.dof) @ u + bias
        tau, saturated = self.constraint.apply(tau_unsat, qdot)
        return {"tau": tau, TASK_ERROR: e, "saturated": bool(saturated.any())}
