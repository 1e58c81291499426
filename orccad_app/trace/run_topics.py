"""The topics of a run beyond its events: the robot moving, parameters, phases, state, verdicts.

:class:`RunTopicsRecorder` is the :class:`~orccad_app.trace.recorder.TraceRecorder` of a topic
writer (an MCAP trace, the live Foxglove stream: :class:`~orccad_app.trace.mcap_writer.TopicWriter`)
that also observes the mission run it is attached to — never reaching into it:

- **the robot**: before the run, every robot's geometry on ``/scene`` (from its plant's MJCF
  model, :mod:`orccad_app.trace.scene`); then every body's frame on ``/tf`` every
  ``frame_period_ns`` of simulated time (default 20 ms: 50 frames per second), stamped with
  the instant the plant's state is at: the plant is integrated up to each read and write of its
  ports, and by each frame up to the frame's instant when it is on the plant's timestep grid
  (:meth:`~orccad_app.executive.plant.MujocoPlant.catch_up`: whole steps, so a run with a trace is
  the same run as without) — the robot moves on in the frames while no module reads it
  (between tasks, during an ``await``) — and once more at the end;
- **joint states** (a writer that ``wants_joint_states``: rosbag2): at each instant a module
  reads one of a robot's sensors, the position, velocity and actuator force of its hinge and
  slide joints, from the plant's state at that instant; a floating base's pose with the
  frames;
- **parameters**: at each start of a Robot-Task, the nominal value of every parameter one of
  its type-1 exceptions updates (``/params/<module>/<param>``, then each update);
- **phases and state**: at each change of the automaton's state, ``/mission/state`` (the
  statements it waits at) and ``/mission/phase/<Task>`` for every task whose phase changed;
- **warnings**: the run's warnings about itself (``on_warning``: a real-time run's job records
  lost) on ``/log``;
- **verdicts**: with ``verdicts`` (a function giving every property's verdict on the run so far:
  the property monitor, wired by the caller), ``/properties/<name>`` every
  ``verdict_period_ns`` (default 100 ms, at least 1/1000 of the run's horizon: the evaluation
  reads the whole run so far) and at the end.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from orccad_app.trace.mcap_writer import WARNING, TopicWriter
from orccad_app.trace.recorder import TraceRecorder, plain_value
from orccad_app.trace.state_topics import VerdictSample

if TYPE_CHECKING:
    from orccad_app.mission.run import MissionRun
    from orccad_app.robottask.labels import Phase
    from orccad_app.trace.scene import RobotScene

__all__ = ["RunTopicsRecorder", "trace_recorder", "FRAME_PERIOD_NS", "VERDICT_PERIOD_NS", "MAX_VERDICT_SAMPLES"]

FRAME_PERIOD_NS = 20_000_000
"""The robot's frames are sampled every 20 ms of simulated time (50 Hz)."""
VERDICT_PERIOD_NS = 100_000_000
"""The properties' verdicts are evaluated every 100 ms of simulated time at most..."""
MAX_VERDICT_SAMPLES = 1000
"""... and at most this many times over the run's horizon (each evaluation reads the run so
far: the cost grows with the square of the number of evaluations)."""


class RunTopicsRecorder(TraceRecorder):
    """Writes every event of ``mission_run`` and its state to ``writer`` (see the module
    docstring); :meth:`close` writes the final frames and verdicts, then closes the writer.

    :param writer: the topic writer (MCAP file or live stream).
    :param mission_run: the run it observes (add this recorder as its observer).
    :param verdicts: every property's verdict on the run so far, or ``None``.
    """

    def __init__(self, writer: TopicWriter, mission_run: MissionRun, *,
                 verdicts: Callable[[], list[VerdictSample]] | None = None,
                 frame_period_ns: int = FRAME_PERIOD_NS,
                 verdict_period_ns: int = VERDICT_PERIOD_NS) -> None:
        from orccad_app.trace.scene import robot_scene

        super().__init__(writer)
        self.topics = writer
        writer.signal_roles(mission_run.plan.roles)
        self._run = mission_run
        self._plants = [(plant, robot_scene(name, plant.model))
                        for name, plant in mission_run.plants.items()]
        self._frame_period_ns = frame_period_ns
        self._next_frame_ns = 0
        self._verdicts = verdicts
        self._verdict_period_ns = max(verdict_period_ns,
                                      mission_run.until_ns // MAX_VERDICT_SAMPLES)
        self._next_verdict_ns = 0
        self._tasks = sorted({site.task for site in mission_run.plan.sites})
        self._task_phase: dict[str, int] = {}
        self._closed = False
        self._by_robot = {scene.robot: (plant, scene) for plant, scene in self._plants}
        self._sensed: dict[tuple[str, str], str] = {}
        if writer.wants_joint_states:
            from orccad_app.trace.writers import sensor_ports

            self._sensed = {key: sensor.split(".", 1)[0]
                            for key, sensor in sensor_ports(mission_run.plan).items()}
        self._joints_at: dict[str, int] = {}
        now = mission_run.kernel.now
        writer.scene(now, [scene for _, scene in self._plants])
        self._frames()

    @property
    def scenes(self) -> list[RobotScene]:
        """Every robot's frames and geometry."""
        return [scene for _, scene in self._plants]

    # -- sampling ----------------------------------------------------------------------------

    def _frames(self) -> None:
        for plant, scene in self._plants:
            plant.catch_up()  # no module may read the robot now (between tasks): it moves on
            transforms = scene.transforms(plant.qpos)
            self.topics.transforms(plant.time_ns, transforms)
            for transform in transforms:
                if transform.child_id in scene.floating:
                    self.topics.pose(plant.time_ns, scene.robot, transform)

    def on_read(self, t_ns: int, module: str, port: str, value: Any) -> None:
        """A module read a port: when it is a robot's sensor, the robot's joint state at this
        instant (once per instant), from the plant's own state."""
        super().on_read(t_ns, module, port, value)
        robot = self._sensed.get((module, port))
        if robot is None or self._joints_at.get(robot) == t_ns:
            return
        self._joints_at[robot] = t_ns
        plant, scene = self._by_robot[robot]
        joints, data = scene.joints, plant.data
        if joints.names:
            self.topics.joint_state(plant.time_ns, robot, joints.names,
                                    [float(data.qpos[i]) for i in joints.qpos],
                                    [float(data.qvel[i]) for i in joints.dof],
                                    [float(data.qfrc_actuator[i]) for i in joints.dof])

    def _sample(self, t_ns: int, final: bool = False) -> None:
        if final or t_ns >= self._next_frame_ns:
            self._next_frame_ns = t_ns + self._frame_period_ns
            self._frames()
        if self._verdicts is not None and (final or t_ns >= self._next_verdict_ns):
            self._next_verdict_ns = t_ns + self._verdict_period_ns
            for sample in self._verdicts():
                self.topics.verdict(t_ns, sample)

    # -- mission hooks -----------------------------------------------------------------------

    def on_reaction(self, t_ns: int, inputs: tuple[str, ...], outputs: tuple[str, ...],
                    status: str) -> None:
        super().on_reaction(t_ns, inputs, outputs, status)
        self._sample(t_ns)

    def on_task_start(self, t_ns: int, task: str, site: int, args: dict) -> None:
        super().on_task_start(t_ns, task, site, args)
        modules = self._run.plan.tcs.modules
        for started in (s for s in self._run.plan.sites if s.number == site):
            for update in started.adjustments.values():
                compute = getattr(modules.get(update.module), "compute", None)
                if compute is not None:
                    self.topics.param(t_ns, update.module, update.param,
                                      plain_value(compute.get_param(update.param)))

    def on_state(self, t_ns: int, state: int, phases: dict[int, Phase]) -> None:
        automaton = self._run.plan.automaton
        waiting = automaton.waiting[state] if 0 <= state < len(automaton.waiting) else ()
        self.topics.mission_state(t_ns, state, list(waiting), self._run.reactor.status)
        by_task: dict[str, int] = {}
        for site in self._run.plan.sites:
            phase = int(phases.get(site.number, 0))
            by_task[site.task] = max(by_task.get(site.task, 0), phase)
        for task in self._tasks:
            phase = by_task.get(task, 0)
            if self._task_phase.get(task) != phase:
                self._task_phase[task] = phase
                self.topics.phase(t_ns, task, phase)

    def on_warning(self, t_ns: int, source: str, message: str) -> None:
        """The run's warning about itself, on ``/log``."""
        self.topics.log(t_ns, WARNING, source, message)

    def close(self) -> None:
        """The final frames (the plants are at the run's last instant) and verdicts, then
        close the writer (idempotent)."""
        if self._closed:
            return
        self._closed = True
        try:
            self._sample(self._run.kernel.now, final=True)
        finally:
            self.topics.close()


def trace_recorder(writer: Any, mission_run: MissionRun, *,
                   verdicts: Callable[[], list[VerdictSample]] | None = None) -> TraceRecorder:
    """The recorder of ``writer`` on ``mission_run``: a :class:`RunTopicsRecorder` for a topic
    writer (MCAP, live), a plain :class:`~orccad_app.trace.recorder.TraceRecorder` (events
    only) for CSV. Add it as an observer of the run; close it when the run ends."""
    if isinstance(writer, TopicWriter):
        return RunTopicsRecorder(writer, mission_run, verdicts=verdicts)
    return TraceRecorder(writer)
