"""Robot types: a physical resource described by one MJCF file.

The same MJCF file feeds MuJoCo (the simulated plant) and Pinocchio (the controller's
models M̂, N̂ and kinematics), so the two cannot drift apart. :meth:`RobotType.from_mjcf`
reads everything it can from the file:

- joints (hinge/slide, one per degree of freedom) → ``resources`` and joint limits
  ``range`` [rad];
- ``jointpos`` / ``jointvel`` sensors → the ``q`` and ``qdot`` sensor ports;
- ``motor`` actuators → the ``tau`` actuator port and torque limits ``ctrlrange`` [N·m];
- optional ``<custom><numeric name="actuator_alpha"/"actuator_beta">`` → the torque–speed
  line of :class:`~orccad_app.control.constraints.ActuatorConstraint`;
- a ``<site>`` named ``end_effector`` → the frame of Cartesian task functions.

Port naming follows the plan language: a robot declared ``robot arm : arm3dof;`` exposes
``arm.q`` and ``arm.qdot`` (sensors: ``out`` ports, the robot produces them) and
``arm.tau`` (actuator: an ``in`` port).
"""

from __future__ import annotations

import enum
import functools
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any, ClassVar

import numpy as np

from orccad_app.control.constraints import ActuatorConstraint
from orccad_app.control.errors import ControlError
from orccad_app.control.ports import PortSpec, Timing
from orccad_app.control.params import ParamSpec, close_matches, resolve_params
from orccad_app.control.plant_extension import PlantExtension

__all__ = ["RobotPort", "RobotType", "IdleBehaviour", "SensorSetting", "SensorParam"]


class IdleBehaviour(enum.Enum):
    """What holds a robot while no Module-Task drives its actuators: before the first
    Robot-Task, between Robot-Tasks, after the last one, and from a task's start until its
    first command. Declared by the robot type (:attr:`RobotType.idle`); the executive applies
    it (docs/robot-tasks.md, *Idle behaviour*)."""

    FREE = "free"
    """Actuators at zero: the robot moves under gravity and its own dynamics."""
    BRAKES = "brakes"
    """Joint brakes: the joints are locked at their position when the robot went idle."""
    HOLD = "hold"
    """A holding law: gravity (and Coriolis) compensation plus a stiff PD at the position
    when the robot went idle, clamped to the torque limits."""


class SensorSetting(enum.Enum):
    """What a :class:`SensorParam` sets on its sensor ports."""

    NOISE_STD = "noise_std"
    """Standard deviation of the additive Gaussian noise, drawn from the run's seed."""
    QUANTIZATION = "quantization"
    """Quantization step: the measured value is rounded to a multiple of it (0: none)."""


@dataclass(frozen=True)
class SensorParam:
    """A robot type parameter that sets the noise or the quantization of sensor ports.

    Declared by a plugin in :attr:`RobotType.sensor_params`; set from a mission
    (``robot arm : arm3dof(noise_std = 1e-4);``), from the command line
    (``orccad run --set arm.noise_std=1e-4``) or varied by a campaign like any robot
    type parameter. Its value is a real ``>= 0`` (``<= maximum`` when given) in ``unit``,
    the unit of its ports.

    :param name: the parameter's name (``noise_std``).
    :param ports: the sensor ports it sets (``("q",)``).
    :param setting: noise or quantization (:class:`SensorSetting`).
    :param default: its value when not set [unit].
    :param unit: the unit of the value and of the ports (``[rad]``).
    :param doc: what it models (``encoder noise on q``).
    :param maximum: the largest accepted value [unit], ``None`` for no bound.
    """

    name: str
    ports: tuple[str, ...]
    setting: SensorSetting
    default: float
    unit: str
    doc: str
    maximum: float | None = None

    @property
    def spec(self) -> ParamSpec:
        """The parameter as a :class:`ParamSpec`: a finite real in ``[0, maximum]``."""
        return ParamSpec(self.name, "float", float(self.default), f"{self.doc} {self.unit}",
                         minimum=0.0, maximum=self.maximum)


@dataclass(frozen=True)
class RobotPort:
    """A sensor or actuator port of a robot, bound to MuJoCo elements.

    ``mj_names`` are the MuJoCo sensor names (sensor ports) or actuator names (actuator
    ports), one per component, in joint order. ``unit`` documents the value ([rad],
    [rad/s], [N·m]). ``quantum`` (quantization step) and ``noise_std`` are the defaults
    the executive applies when sampling a sensor.
    """

    spec: PortSpec
    unit: str
    mj_names: tuple[str, ...]
    quantum: float | None = None
    noise_std: float = 0.0

    @property
    def name(self) -> str:
        """The port name, e.g. ``"q"``."""
        return self.spec.name

    @property
    def dim(self) -> int:
        """Number of components."""
        return len(self.mj_names)


@dataclass(frozen=True, eq=False)
class RobotType:
    """A robot model provided by a plugin. See the module docstring."""

    name: str
    summary: str
    mjcf_path: Path
    resources: tuple[str, ...]
    sensors: tuple[RobotPort, ...]
    actuators: tuple[RobotPort, ...]
    actuator_constraint: ActuatorConstraint
    joint_limits: tuple[np.ndarray, np.ndarray]
    end_effector: str | None = None
    timestep_s: float = 0.001
    params: tuple[ParamSpec, ...] = ()
    param_values: Mapping[str, Any] = field(default_factory=dict)
    idle: IdleBehaviour = IdleBehaviour.FREE
    """What holds the robot while nothing drives its actuators (:class:`IdleBehaviour`)."""
    idle_gains: tuple[float, float] = (400.0, 40.0)
    """``(kp [N·m/rad], kv [N·m·s/rad])`` of the ``hold`` idle behaviour."""

    sensor_params: tuple[SensorParam, ...] = ()
    """Parameters setting the noise and quantization of sensor ports (:class:`SensorParam`)."""
    sensor_values: Mapping[str, float] = field(default_factory=dict)
    """The values given to :attr:`sensor_params` (by :meth:`configure`)."""

    run_horizon_s: ClassVar[float] = 0.0
    """Extension point: the default simulated-time limit of ``orccad run`` for missions on
    this robot [s] (0: the command's default, 60 s); a subclass sets it (an AUV mission
    lasts minutes)."""

    def __post_init__(self) -> None:
        sensors = {port.name for port in self.sensors}
        names = {spec.name for spec in self.params}
        for param in self.sensor_params:
            if param.name in names:
                raise ControlError(f"robot type {self.name!r}: parameter {param.name!r} is "
                                   f"declared twice")
            names.add(param.name)
            for port in param.ports:
                if port not in sensors:
                    raise ControlError(
                        f"robot type {self.name!r}: sensor parameter {param.name!r} names "
                        f"no sensor port {port!r} (sensors: {', '.join(sorted(sensors))})")
            param.spec.coerce(param.default, f"robot type {self.name!r}")

    @property
    def parameters(self) -> tuple[ParamSpec, ...]:
        """Every parameter of the type: :attr:`params`, then the :attr:`sensor_params`."""
        return self.params + tuple(param.spec for param in self.sensor_params)

    def sensor_noise(self) -> dict[str, float]:
        """Sensor port -> standard deviation of its noise [port unit]: the ports' defaults,
        then the :attr:`sensor_params` (their values, or their defaults)."""
        return self._sensor_setting(SensorSetting.NOISE_STD,
                                    {p.name: p.noise_std for p in self.sensors})

    def sensor_quantization(self) -> dict[str, float]:
        """Sensor port -> quantization step [port unit] (0: none), as :meth:`sensor_noise`."""
        return self._sensor_setting(SensorSetting.QUANTIZATION,
                                    {p.name: p.quantum or 0.0 for p in self.sensors})

    def _sensor_setting(self, setting: SensorSetting,
                        values: dict[str, float]) -> dict[str, float]:
        for param in self.sensor_params:
            if param.setting is setting:
                value = float(self.sensor_values.get(param.name, param.default))
                values.update(dict.fromkeys(param.ports, value))
        return values

    def plant_extension(self) -> PlantExtension | None:
        """Extension point: a fresh :class:`PlantExtension` for one run's plant (extra
        physics, sensor ports, faults), or ``None`` (the default: the MJCF model alone)."""
        return None

    @property
    def dof(self) -> int:
        """Number of joints (= dimension of ``q``)."""
        return len(self.resources)

    @property
    def torque_limits(self) -> tuple[np.ndarray, np.ndarray]:
        """``(tau_min, tau_max)`` [N·m] per joint."""
        return self.actuator_constraint.tau_min, self.actuator_constraint.tau_max

    @property
    def ports(self) -> tuple[RobotPort, ...]:
        """Sensor ports then actuator ports."""
        return self.sensors + self.actuators

    @property
    def default_timing(self) -> Timing:
        """The plant's integration step as a timing: ``period_ns`` = MJCF timestep."""
        return Timing(round(self.timestep_s * 1e9), 0)

    def port(self, name: str) -> RobotPort:
        """The port ``name`` (``q``, ``qdot``, ``tau``…); raises naming close matches."""
        for port in self.ports:
            if port.name == name:
                return port
        names = [port.name for port in self.ports]
        raise ControlError(f"robot type {self.name!r} has no port {name!r}"
                           f"{close_matches(name, names)}; its ports: {', '.join(names)}")

    def configure(self, params: Mapping[str, Any]) -> RobotType:
        """This type with type parameters (``robot auv : auv(battery_wh = 400.0)``) and sensor
        parameters (``robot arm : arm3dof(noise_std = 1e-4)``), checked against
        :attr:`parameters` (unknown names, types, ranges, finiteness)."""
        values = resolve_params(self.name, self.parameters, params)
        sensors = {param.name for param in self.sensor_params}
        return replace(self, param_values={k: v for k, v in values.items() if k not in sensors},
                       sensor_values={k: v for k, v in values.items() if k in sensors})

    def pinocchio_model(self) -> Any:
        """A fresh ``pinocchio.Model`` built from :attr:`mjcf_path` (``buildModelFromMJCF``).

        Armature and joint damping are read from the file (``model.armature``,
        ``model.damping``); gravity is Pinocchio's default (0, 0, -9.81) m/s² like MuJoCo's.
        """
        return _pinocchio_model(str(self.mjcf_path)).copy()

    def mujoco_model(self) -> Any:
        """A fresh ``mujoco.MjModel`` compiled from :attr:`mjcf_path`."""
        import mujoco

        return mujoco.MjModel.from_xml_path(str(self.mjcf_path))

    @classmethod
    def from_mjcf(cls, name: str, path: str | Path, summary: str = "",
                  params: tuple[ParamSpec, ...] = (), **overrides: Any) -> RobotType:
        """Describe the robot in the MJCF file ``path``; see the module docstring."""
        import mujoco

        path = Path(path).resolve()
        if not path.is_file():
            raise ControlError(f"robot type {name!r}: MJCF file not found: {path}")
        try:
            model = mujoco.MjModel.from_xml_path(str(path))
        except ValueError as error:
            raise ControlError(f"robot type {name!r}: cannot load {path}: {error}") from None
        fields = _describe(model, name)
        fields.update(overrides)
        return cls(name=name, summary=summary, mjcf_path=path, params=params, **fields)


@functools.lru_cache(maxsize=16)
def _pinocchio_model(path: str) -> Any:
    import pinocchio

    return pinocchio.buildModelFromMJCF(path)


def _names(model: Any, obj: Any, ids: list[int]) -> tuple[str, ...]:
    import mujoco

    return tuple(mujoco.mj_id2name(model, obj, i) or f"#{i}" for i in ids)


def _describe(model: Any, name: str) -> dict[str, Any]:
    """Resources, ports, limits and end effector read from a compiled ``MjModel``."""
    import mujoco

    kinds = (int(mujoco.mjtJoint.mjJNT_HINGE), int(mujoco.mjtJoint.mjJNT_SLIDE))
    joints = [j for j in range(model.njnt) if int(model.jnt_type[j]) in kinds]
    if len(joints) != model.nq or model.nq != model.nv:
        raise ControlError(f"robot type {name!r}: only hinge and slide joints are supported")
    dof = len(joints)
    lower = np.where(model.jnt_limited[joints] != 0, model.jnt_range[joints, 0], -np.inf)
    upper = np.where(model.jnt_limited[joints] != 0, model.jnt_range[joints, 1], np.inf)
    sensors = (_sensor_port(model, name, "jointpos", "q", "[rad]"),
               _sensor_port(model, name, "jointvel", "qdot", "[rad/s]"))
    tau, order = _actuator_port(model, name, dof)
    limits = model.actuator_ctrlrange[order]
    constraint = ActuatorConstraint(limits[:, 0], limits[:, 1],
                                    _numeric(model, "actuator_alpha", dof, np.inf),
                                    _numeric(model, "actuator_beta", dof, 0.0))
    site = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_SITE, "end_effector")
    return dict(resources=_names(model, mujoco.mjtObj.mjOBJ_JOINT, joints),
                sensors=sensors, actuators=(tau,), actuator_constraint=constraint,
                joint_limits=(lower, upper),
                end_effector="end_effector" if site >= 0 else None,
                timestep_s=float(model.opt.timestep))


def _sensor_port(model: Any, name: str, element: str, port: str, unit: str) -> RobotPort:
    """The sensor port made of the MJCF ``<element>`` sensors (jointpos, jointvel)."""
    import mujoco

    kind = int(getattr(mujoco.mjtSensor, f"mjSENS_{element.upper()}"))
    ids = sorted((i for i in range(model.nsensor) if int(model.sensor_type[i]) == kind),
                 key=lambda i: model.sensor_objid[i])
    if len(ids) != model.njnt:
        raise ControlError(f"robot type {name!r}: port {port!r} needs one "
                           f"<{element}> sensor per joint, "
                           f"found {len(ids)} for {model.njnt} joints")
    names = _names(model, mujoco.mjtObj.mjOBJ_SENSOR, ids)
    doc = f"joint {'positions' if port == 'q' else 'velocities'} {unit}"
    return RobotPort(PortSpec(port, "out", "vector", len(ids), doc=doc), unit, names)


def _actuator_port(model: Any, name: str, dof: int) -> tuple[RobotPort, list[int]]:
    import mujoco

    if model.nu != dof or not np.all(model.actuator_ctrllimited[: model.nu]):
        raise ControlError(f"robot type {name!r}: port 'tau' needs one motor with a "
                           f"ctrlrange per joint, found {model.nu} for {dof} joints")
    if np.any(model.actuator_gear[: model.nu, 0] != 1.0):
        raise ControlError(f"robot type {name!r}: port 'tau' needs direct-drive motors "
                           f"(gear 1), found gears {model.actuator_gear[: model.nu, 0].tolist()}")
    order = sorted(range(model.nu), key=lambda i: model.actuator_trnid[i, 0])
    names = _names(model, mujoco.mjtObj.mjOBJ_ACTUATOR, order)
    spec = PortSpec("tau", "in", "vector", dof, doc="joint torques [N·m]")
    return RobotPort(spec, "[N·m]", names), order


def _numeric(model: Any, key: str, dof: int, default: float) -> np.ndarray:
    import mujoco

    index = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_NUMERIC, key)
    if index < 0:
        return np.full(dof, default)
    start, size = model.numeric_adr[index], model.numeric_size[index]
    return np.array(model.numeric_data[start:start + size], dtype=float)
