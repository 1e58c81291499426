"""The TCS bridge: Robot-Task instances become what the executive runs.

A checked Robot-Task instance (:class:`~orccad_app.robottask.model.RobotTaskInstance`) becomes
Module-Tasks and connections of a :class:`~orccad_app.tcs.graph.TCS`:

- each module (declared, or an observer the compiler instantiated) is a
  :class:`~orccad_app.tcs.module_task.ModuleTask` named ``prefix + module`` whose compute object
  is the module instance; its timing, processor and priority are the ones declared;
- its ports keep the control library's types (``vector`` of ``dim``, ``float``, ``bool``,
  ``event``, ``string``); an *optional* input left unconnected is not a port of the TCS (the
  module then uses its documented fallback), so every TCS input is fed;
- the robot is a :class:`~orccad_app.tcs.module_task.PhysicalResource` named like the robot
  (``arm``: sensors ``arm.q``, ``arm.qdot``, actuator ``arm.tau``);
- values read before any write are ``None`` (the modules' "no value yet"), never a zero that
  a control law would act upon.
"""

from __future__ import annotations

from orccad_app.control.module import PortSpec
from orccad_app.diagnostics import OrccadError
from orccad_app.control.robot import RobotType
from orccad_app.robottask.model import RobotTaskInstance
from orccad_app.tcs.graph import TCS
from orccad_app.tcs.module_task import Activation, ModuleTask, PhysicalResource
from orccad_app.tcs.port import Port
from orccad_app.tcs.protocol import Protocol
from orccad_app.executive.sporadic import PUSHED_ON_WRITE

__all__ = ["tcs_port", "robot_resource", "instance_module_tasks", "add_instance", "task_tcs"]


def tcs_port(spec: PortSpec) -> Port:
    """The TCS port of a control-library ``PortSpec`` (``dim`` 1 for non-vectors)."""
    return Port(spec.name, spec.direction, spec.type, spec.dim or 1)


def robot_resource(name: str, robot_type: RobotType) -> PhysicalResource:
    """The physical resource ``name`` of a robot type: its sensor and actuator ports."""
    return PhysicalResource(name, tuple(tcs_port(port.spec) for port in robot_type.ports))


def instance_module_tasks(instance: RobotTaskInstance, prefix: str = "") -> dict[str, ModuleTask]:
    """The Module-Tasks of a task instance, by local module name (named ``prefix + name``)."""
    fed = {(c.target, c.target_port) for c in instance.connections}
    tasks: dict[str, ModuleTask] = {}
    for name, spec in instance.modules.items():
        ports = tuple(tcs_port(port) for port in spec.instance.ports
                      if port.direction == "out" or (name, port.name) in fed)
        timing = spec.timing
        tasks[name] = ModuleTask(prefix + name, timing.period_ns, timing.wcet_ns, spec.instance,
                                 ports, processor=spec.processor, priority=spec.priority,
                                 bcet_ns=timing.bcet_ns, kind=spec.kind.name, location=spec.loc,
                                 activation=spec.activation)
    return tasks


def add_instance(tcs: TCS, instance: RobotTaskInstance, prefix: str = "") -> dict[str, str]:
    """Add the Module-Tasks and connections of ``instance`` to ``tcs`` (whose resources must
    include the instance's robot); return local module name -> TCS name."""
    names = {}
    for local, task in instance_module_tasks(instance, prefix).items():
        tcs.add(task)
        names[local] = task.name
    robot = instance.robot_name

    def end(module: str, port: str) -> str:
        return f"{module if module == robot else names[module]}.{port}"

    for c in instance.connections:
        tcs.connect(end(c.source, c.source_port), end(c.target, c.target_port), c.protocol,
                    c.loc)
    _check_interrupted(instance)
    return names


def _check_interrupted(instance: RobotTaskInstance) -> None:
    """A sporadic module needs an input whose writes interrupt it: written by another module
    on its processor, or across the bus under a protocol that sends each write."""
    modules = instance.modules
    for name, spec in modules.items():
        if spec.activation is not Activation.SPORADIC:
            continue
        if not any(c.target == name and c.source in modules
                   and (modules[c.source].processor == spec.processor
                        or Protocol(c.protocol) in PUSHED_ON_WRITE)
                   for c in instance.connections):
            raise OrccadError(f"sporadic module '{name}' has no input whose writes can release "
                              f"it: connect an output of another module to it (on another "
                              f"processor: over asyn/asyn, asyn/syn or asyn/synF, which send "
                              f"each write); robot sensors are sampled, never written",
                              spec.loc)


def task_tcs(instance: RobotTaskInstance) -> TCS:
    """The TCS of one Robot-Task instance alone (module names unprefixed)."""
    tcs = TCS(instance.task.name)
    tcs.add(robot_resource(instance.robot_name,
                           instance.context.require_robot(f"Robot-Task '{instance.task.name}'")))
    add_instance(tcs, instance)
    return tcs
