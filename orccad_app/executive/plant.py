"""Plant coupling: a MuJoCo model advanced between events (docs/design.md, *Plant coupling*; RR-1801 §6.1).

:class:`MujocoPlant` wraps an MJCF model as the physical resource of a TCS. Its ports:

- producer (sensor) ports ``q`` (``qpos``, dim ``nq``), ``qdot`` (``qvel``, dim ``nv``) and one
  port per named MJCF ``<sensor>`` (dim ``sensor_dim``), sampled at the instant of the read;
- consumer (actuator) port ``tau`` (``ctrl``, dim ``nu``), held until the next write
  (zero-order hold) and clamped to the torque limits.

**Time coupling.** The plant integrates in steps of the model's ``opt.timestep`` on the grid
``k · timestep`` and is brought *exactly* to the instant of every read and write (and to the
end of a run): when that instant falls between two grid points, a shorter step reaches it,
and the next advance first completes the step back onto the grid. A read at ``t`` thus sees the
state at ``t`` and a write at ``t`` acts from ``t``: a Module-Task's execution time delays its
torque by exactly that time, even below one timestep (RR-1801 §6.2's point). Instants on the
grid cost no extra step.

**Sensors.** ``noise_std`` adds Gaussian noise per port (stream ``plant/<name>/<port>`` of the
run's seed), then ``quantization`` rounds to multiples of the step per port.

**Extensions.** Physics MuJoCo lacks (hydrostatics, a battery, a leak), extra sensor ports and
named faults come from a :class:`PlantExtension` (``extension=``, or :meth:`MujocoPlant.extend`):
the plant calls ``extension.step(dt_s)`` before every integration step (whole or partial), reads
the extension's sensor ports like MJCF sensors (noise and quantization included) and applies
``--inject ROBOT.FAULT=VALUE@T`` through :meth:`MujocoPlant.inject`. A robot type provides one by
defining ``plant_extension()`` (see docs/plugins.md, *Plant extensions*).

**Idle behaviour.** With ``idle=`` (a robot type's
:class:`~orccad_app.control.robot.IdleBehaviour`), the plant is held by it while nothing drives
it: from the start until the first write of ``tau``, and from :meth:`MujocoPlant.go_idle` (its
last driving Module-Task killed) until the next write (:mod:`orccad_app.executive.idle`).
Without it the last command is held, as in a bare TCS.

**Divergence.** After each advance, non-finite ``qpos``/``qvel`` or a new MuJoCo warning
(bad ``qacc``/``qpos``/``qvel``/``ctrl``; MuJoCo resets the state on those) raises
:class:`PlantDivergenceError`, whose message (the run's ``reason`` in its report) quotes
MuJoCo's warning text. MuJoCo's warnings are routed to this module
(``mujoco.set_mju_user_warning``), so no ``MUJOCO_LOG.TXT`` is left in the user's working
directory.
"""

from __future__ import annotations

import math
from typing import Any, Mapping

import mujoco
import numpy as np

from orccad_app.control.plant_extension import PlantExtension
from orccad_app.diagnostics import OrccadError
from orccad_app.executive.idle import IdleBehaviour, IdleHold
from orccad_app.executive.kernel import EventClass, Kernel
from orccad_app.tcs.module_task import PhysicalResource

__all__ = ["MujocoPlant", "PlantDivergenceError", "PlantExtension"]

_WATCHED_WARNINGS = (mujoco.mjtWarning.mjWARN_BADQACC, mujoco.mjtWarning.mjWARN_BADQPOS,
                     mujoco.mjtWarning.mjWARN_BADQVEL, mujoco.mjtWarning.mjWARN_BADCTRL)
_WATCHED_INDEX = np.array([int(w) for w in _WATCHED_WARNINGS])
_WATCHED_SLICE = slice(int(_WATCHED_INDEX.min()), int(_WATCHED_INDEX.max()) + 1)
if _WATCHED_SLICE.stop - _WATCHED_SLICE.start != len(_WATCHED_INDEX):  # not contiguous
    _WATCHED_SLICE = slice(0, None)
_NOISE_BLOCK = 256
"""Sensor noise samples drawn at once per port (see ``MujocoPlant._noise_draw``)."""
_clip = np.clip if not hasattr(np, "_core") else getattr(np._core.umath, "clip", np.clip)
"""``np.clip``'s ufunc without its Python wrapper (same operation)."""


_MUJOCO_WARNINGS: list[str] = []
"""MuJoCo's warning messages of this process, in order (see :func:`_mujoco_warning`)."""


def _mujoco_warning(message: str) -> None:
    """MuJoCo's warning handler: keep the message for the run's report. Without a handler
    MuJoCo appends it to ``MUJOCO_LOG.TXT`` in the user's working directory and prints it."""
    _MUJOCO_WARNINGS.append(" ".join(message.split()))


mujoco.set_mju_user_warning(_mujoco_warning)


class PlantDivergenceError(OrccadError):
    """The physics diverged (non-finite state or a MuJoCo instability warning)."""

    exit_status = 1


def _load(xml: str | None, path: str | None) -> mujoco.MjModel:
    if (xml is None) == (path is None):
        raise OrccadError("MujocoPlant needs exactly one of xml= (an MJCF string) or path=")
    try:
        if xml is not None:
            return mujoco.MjModel.from_xml_string(xml)
        return mujoco.MjModel.from_xml_path(str(path))
    except ValueError as error:
        raise OrccadError(f"cannot load MJCF model {path or '<string>'}: {error}") from None


class MujocoPlant:
    """A MuJoCo model as the physical resource ``name``.

    :param name: the resource's name in the TCS (e.g. ``arm``: ports ``arm.q``, ``arm.tau``).
    :param xml: MJCF text; or
    :param path: an MJCF file.
    :param noise_std: per sensor port, the standard deviation of additive Gaussian noise
        (in the port's unit: [rad], [rad/s], ...).
    :param quantization: per sensor port, the quantization step (same unit).
    :param torque_limits: symmetric bound(s) on ``tau`` [N·m] (scalar or per actuator);
        default: the actuators' ``ctrlrange`` where ``ctrllimited``, else none.
    :param qpos0: initial joint positions (default: the model's ``qpos0``).
    :param qvel0: initial joint velocities (default zero).
    :param extension: a :class:`PlantExtension` (extra physics, sensors, faults).
    :param idle: what holds the robot while nothing drives it (``None``: the last command).
    :param idle_gains: ``(kp [N·m/rad], kv [N·m·s/rad])`` of the ``hold`` behaviour.
    """

    def __init__(self, name: str, *, xml: str | None = None, path: str | None = None,
                 noise_std: Mapping[str, float] | None = None,
                 quantization: Mapping[str, float] | None = None,
                 torque_limits: Any = None, qpos0: Any = None, qvel0: Any = None,
                 extension: PlantExtension | None = None,
                 idle: IdleBehaviour | None = None,
                 idle_gains: tuple[float, float] = (400.0, 40.0)) -> None:
        self.model = _load(xml, path)
        self.extension: PlantExtension | None = None
        self.data = mujoco.MjData(self.model)
        # views into MuJoCo's arrays (the same memory for the life of ``data``)
        self._qpos, self._qvel, self._ctrl = self.data.qpos, self.data.qvel, self.data.ctrl
        self._option = self.model.opt
        self._warning_view = self.data.warning.number[_WATCHED_SLICE]
        self.name = name
        self.timestep_ns = int(round(self.model.opt.timestep * 1e9))
        if self.timestep_ns <= 0:
            raise OrccadError(f"plant '{name}': timestep {self.model.opt.timestep} s is below 1 ns")
        self._readers = self._sensor_readers()
        self._observers: dict[str, Any] = {}
        """Per port, what :meth:`observe` returns (built at the first observation)."""
        self.resource = self._resource()
        if extension is not None:
            self.extend(extension)
        self._noise = self._per_port("noise_std", noise_std)
        self._quantum = self._per_port("quantization", quantization)
        self._low, self._high = self._limits(torque_limits)
        if qpos0 is not None:
            self.data.qpos[:] = qpos0
        if qvel0 is not None:
            self.data.qvel[:] = qvel0
        mujoco.mj_forward(self.model, self.data)
        self.steps = 0
        """Integration steps taken (whole and partial)."""
        self._time_ns = 0
        self.saturations = 0
        """Actuator writes that the torque limits clamped."""
        self._kernel: Kernel  # set by attach(), before the run
        self._attached = False
        self._streams: dict[str, np.random.Generator] = {}
        self._noise_blocks: dict[str, list] = {}
        """Per noisy port: [noise block, next index, its std, the standard normals]."""
        self._warnings = self._warning_counts()
        self._warning_total = sum(self._warning_view.tolist())
        self._messages_seen = len(_MUJOCO_WARNINGS)
        self.notify: Any = None
        """``notify(signal, value)``, set by the simulation: idle changes as signals."""
        self._idle: IdleHold | None = None
        self._idle_on = False
        if idle is not None:
            self._idle = IdleHold(idle, self.model, self._low, self._high, *idle_gains)
            self._idle_on = True
            self._idle.engage(self.data)

    @property
    def idle(self) -> bool:
        """Whether the idle behaviour holds the robot now."""
        return self._idle_on

    def go_idle(self) -> None:
        """Nothing drives the robot any more: its idle behaviour holds it from now on."""
        if self._idle is None or self._idle_on:
            return
        self.advance_to(self._kernel.now)
        self._idle_on = True
        self._idle.engage(self.data)
        if self.notify is not None:
            self.notify(f"{self.name}.idle", self._idle.behaviour.value)

    def _holding(self) -> Any:
        """The per-step idle action now, or ``None``."""
        idle = self._idle
        if not self._idle_on or idle is None or idle.behaviour is IdleBehaviour.FREE:
            return None
        return idle.before_step

    # -- construction ------------------------------------------------------------------------

    def _sensor_readers(self) -> dict[str, Any]:
        model, data = self.model, self.data
        readers: dict[str, Any] = {"q": self._qpos.copy, "qdot": self._qvel.copy}
        for index in range(model.nsensor):
            sensor = model.sensor(index)
            if not sensor.name or sensor.name in readers or sensor.name == "tau":
                continue
            start, dim = int(model.sensor_adr[index]), int(model.sensor_dim[index])
            readers[sensor.name] = (lambda a=start, b=start + dim: data.sensordata[a:b].copy())
        return readers

    def _resource(self) -> PhysicalResource:
        dims = {"q": self.model.nq, "qdot": self.model.nv}
        for index in range(self.model.nsensor):
            dims.setdefault(self.model.sensor(index).name, int(self.model.sensor_dim[index]))
        ports = [PhysicalResource.sensor(port, dims[port]) for port in self._readers]
        if self.model.nu:
            ports.append(PhysicalResource.actuator("tau", self.model.nu))
        return PhysicalResource(self.name, tuple(ports))

    def extend(self, extension: PlantExtension) -> None:
        """Attach ``extension`` (before the run): its sensors become ports of the plant."""
        if self.extension is not None:
            raise OrccadError(f"plant '{self.name}' already has an extension")
        self.extension = extension
        self._observers.clear()
        extension.bind(self.model, self.data)
        for port in extension.sensors:
            self._readers[port] = (lambda p=port: np.array(extension.read(p), dtype=float))
        ports = [p for p in self.resource.ports if p.name not in extension.sensors]
        ports += [PhysicalResource.sensor(port, int(dim))
                  for port, dim in extension.sensors.items()]
        self.resource = PhysicalResource(self.name, tuple(ports))

    def inject(self, fault: str, value: Any) -> None:
        """Apply the extension's fault ``fault`` now (``--inject ROBOT.FAULT=VALUE@T``)."""
        extension = self.extension
        if extension is None or fault not in extension.faults:
            faults = extension.faults if extension is not None else {}
            raise OrccadError(f"plant '{self.name}' has no fault '{fault}' "
                              f"(faults: {', '.join(faults) or 'none'})")
        extension.check_fault(fault, value)
        if self._attached:
            self.advance_to(self._kernel.now)
        extension.inject(fault, value)

    def _per_port(self, label: str, values: Mapping[str, float] | None) -> dict[str, float]:
        values = dict(values or {})
        for port, value in values.items():
            if port not in self._readers:
                raise OrccadError(f"plant '{self.name}': {label} for unknown sensor port "
                                  f"'{port}' (sensors: {', '.join(self._readers)})")
            if not value >= 0:
                raise OrccadError(f"plant '{self.name}': {label}['{port}'] must be >= 0, "
                                  f"got {value!r}")
        return {port: float(value) for port, value in values.items() if value > 0}

    def _limits(self, torque_limits: Any) -> tuple[np.ndarray, np.ndarray]:
        nu = self.model.nu
        if torque_limits is not None:
            bound = np.broadcast_to(np.abs(np.asarray(torque_limits, dtype=float)), (nu,))
            return -bound.copy(), bound.copy()
        low = np.full(nu, -np.inf)
        high = np.full(nu, np.inf)
        limited = self.model.actuator_ctrllimited.astype(bool)
        low[limited] = self.model.actuator_ctrlrange[limited, 0]
        high[limited] = self.model.actuator_ctrlrange[limited, 1]
        return low, high

    def _announce_idle(self, _: object) -> None:
        if self._idle_on and self._idle is not None and self.notify is not None:
            self.notify(f"{self.name}.idle", self._idle.behaviour.value)

    def attach(self, kernel: Kernel) -> None:
        """Bind to the simulation's kernel (clock and random streams)."""
        self._kernel = kernel
        self._attached = True
        if self._idle_on:
            kernel.schedule(kernel.now, EventClass.CONTROL, self._announce_idle)

    # -- coupling ----------------------------------------------------------------------------

    @property
    def time_ns(self) -> int:
        """The plant's integrated time [ns]."""
        return self._time_ns

    def advance_to(self, time_ns: int) -> None:
        """Integrate up to ``time_ns`` exactly: back onto the timestep grid, whole steps,
        then a partial step to an instant between grid points."""
        now = self._time_ns
        if time_ns <= now:
            return
        dt = self.timestep_ns
        offset = now % dt
        if offset:
            boundary = now - offset + dt
            if time_ns < boundary:
                self._partial(time_ns - now)
                self._check(time_ns)
                return
            self._partial(boundary - now)
            now = boundary
        count = (time_ns - now) // dt
        if count > 0:
            model, data, step = self.model, self.data, mujoco.mj_step
            extension = self.extension
            hold = self._holding()
            if extension is None and hold is None:
                for _ in range(count):
                    step(model, data)
            else:
                dt_s = model.opt.timestep
                for _ in range(count):
                    if hold is not None:
                        hold(data)
                    if extension is not None:
                        extension.step(dt_s)
                    step(model, data)
            self.steps += count
            self._time_ns = now = now + count * dt
        if time_ns > now:
            self._partial(time_ns - now)
        self._check(time_ns)

    def _partial(self, duration_ns: int) -> None:
        """One step shorter than the timestep."""
        option = self._option
        full = option.timestep
        option.timestep = duration_ns / 1e9
        hold = self._holding()
        if hold is not None:
            hold(self.data)
        if self.extension is not None:
            self.extension.step(option.timestep)
        try:
            mujoco.mj_step(self.model, self.data)
        finally:
            option.timestep = full
        self.steps += 1
        self._time_ns += duration_ns

    def _warning_counts(self) -> tuple[int, ...]:
        return tuple(self.data.warning.number[_WATCHED_INDEX].tolist())

    def _check(self, time_ns: int) -> None:
        # one sum each, on lists (3 floats: cheaper than numpy's reductions): any NaN or
        # infinity makes it non-finite; the watched warning counters are one view
        if math.isfinite(sum(self._qpos.tolist()) + sum(self._qvel.tolist())) and \
                sum(self._warning_view.tolist()) == self._warning_total:
            return
        finite = math.isfinite(sum(self._qpos.tolist()) + sum(self._qvel.tolist()))
        counts = self._warning_counts()
        raised = [w.name for w, old, new in zip(_WATCHED_WARNINGS, self._warnings, counts)
                  if new > old]
        self._warnings = counts
        self._warning_total = sum(self._warning_view.tolist())
        if finite and not raised:  # another counter of the view moved: not a divergence
            return
        what = ", ".join(raised) if raised else "non-finite qpos/qvel"
        said = list(dict.fromkeys(_MUJOCO_WARNINGS[self._messages_seen:]))
        self._messages_seen = len(_MUJOCO_WARNINGS)
        mujoco_said = f"; MuJoCo: {' / '.join(said)}" if said else ""
        raise PlantDivergenceError(f"plant '{self.name}' diverged before t = {time_ns} ns "
                                   f"({what}{mujoco_said}); reduce the timestep or the gains")

    def sample(self, port: str) -> np.ndarray:
        """The sensor ``port`` now (noise and quantization applied)."""
        now = self._kernel.now
        if now > self._time_ns:
            self.advance_to(now)
        value = self._readers[port]()
        std = self._noise.get(port)
        if std:
            value += self._noise_draw(port, std, value.shape)
        quantum = self._quantum.get(port)
        if quantum:
            value = np.round(value / quantum) * quantum
        return value

    def _noise_draw(self, port: str, std: float, shape: tuple[int, ...]) -> np.ndarray:
        """``stream.normal(0.0, std, shape)`` of the port's stream, drawn :data:`_NOISE_BLOCK`
        samples at a time: ``Generator.normal`` computes ``loc + scale * z`` over the stream's
        standard normals ``z`` in order, and so does this from a block of
        ``standard_normal`` (the same draws), so the noise is bit-identical."""
        size = math.prod(shape)
        block = self._noise_blocks.get(port)
        if block is None or block[1] + size > block[0].size or block[2] != std:
            stream = self._streams.get(port)
            if stream is None:
                stream = self._streams[port] = self._kernel.stream(f"plant/{self.name}/{port}")
            rest = block[3][block[1]:] if block is not None else np.empty(0)
            raw = np.concatenate([rest, stream.standard_normal(_NOISE_BLOCK * max(size, 1))])
            block = [np.add(0.0, np.multiply(std, raw)), 0, std, raw]
            self._noise_blocks[port] = block
        start = block[1]
        block[1] = start + size
        return block[0][start:start + size].reshape(shape)

    def catch_up(self) -> None:
        """Integrate up to the kernel's now when now is on the plant's timestep grid (whole
        steps: the integration is the one the next read or write would do, so the run is
        unchanged); otherwise stay at the plant's last instant (at most one timestep old).
        For observers of the plant's state (monitors, the trace's frames) while no module
        reads the robot."""
        now = self._kernel.now if self._attached else self._time_ns
        if now > self._time_ns and now % self.timestep_ns == 0:
            self.advance_to(now)

    def observe(self, port: str) -> np.ndarray:
        """The true value of ``port`` now, for monitors (signal properties): no noise, no
        sensor fault (an extension's ``true_value`` when it has one), the held command for
        the actuator ``tau``. The plant is brought to now only when now is on its timestep
        grid, which leaves the integration unchanged; otherwise the value is the state at the
        plant's last instant (at most one timestep old). Observing never changes a run."""
        self.catch_up()
        observer = self._observers.get(port)
        if observer is None:
            observer = self._observers[port] = self._observer(port)
        return observer()

    def _observer(self, port: str) -> Any:
        """What :meth:`observe` calls for ``port`` (chosen once per port)."""
        extension = self.extension
        if extension is not None and port in extension.sensors and hasattr(extension,
                                                                           "true_value"):
            return lambda: np.asarray(extension.true_value(port), dtype=float)
        if port == "tau" and port not in self._readers:
            return self._ctrl.copy
        reader = self._readers[port]
        if port in ("q", "qdot") or port not in (extension.sensors if extension else ()):
            return reader  # float64 copies of MuJoCo's arrays already
        return lambda: np.asarray(reader(), dtype=float)

    def actuate(self, port: str, value: Any) -> None:
        """Hold ``value`` on the actuator ``port`` (``tau``) from now on, clamped."""
        now = self._kernel.now
        if now > self._time_ns:
            self.advance_to(now)
        command = np.asarray(value, dtype=float)
        if command.shape != self._low.shape:
            command = np.broadcast_to(command, self._low.shape)
        clamped = _clip(command, self._low, self._high)
        if clamped.tolist() != command.tolist():  # NaN != NaN, as (clamped != command).any()
            self.saturations += 1
        self._ctrl[:] = clamped
        if self._idle_on:
            self._idle_on = False
            if self.notify is not None and self._idle is not None:
                self.notify(f"{self.name}.driven", True)

    # -- accessors ---------------------------------------------------------------------------

    @property
    def qpos(self) -> np.ndarray:
        """Joint positions at the plant's time (a copy) [rad or m]."""
        return self.data.qpos.copy()

    @property
    def qvel(self) -> np.ndarray:
        """Joint velocities at the plant's time (a copy) [rad/s or m/s]."""
        return self.data.qvel.copy()

    @property
    def ctrl(self) -> np.ndarray:
        """The held actuator command (a copy) [N·m]."""
        return self.data.ctrl.copy()

    def energy(self) -> float:
        """Potential + kinetic energy at the plant's time [J]."""
        mujoco.mj_energyPos(self.model, self.data)
        mujoco.mj_energyVel(self.model, self.data)
        return float(self.data.energy[0] + self.data.energy[1])
