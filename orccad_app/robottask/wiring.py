"""Connections of a Robot-Task's Module-Tasks, checked (RR-1801 §3.2).

``connect a.b -> c.d : protocol`` joins one producer port to one consumer port. Checked:
both ends exist (a module of the task or its robot), the source is an output and the target
an input, types and vector dimensions agree, each input is fed once. Modules that the
compiler instantiated — the law's default Module-Tasks and the observers named in ``from`` or
in a condition — are wired by name: each input reads the robot sensor of the same name, else
the module output of that name (``q`` from ``arm.q``, ``e`` from the control law), and an
output named like a robot actuator drives it (``ctrl.tau -> arm.tau``). Coherence: every
required input is fed, every module can receive its inputs (``tracking_error`` needs ``e``,
or ``q`` and ``qd``), and every actuator of the task's robot is driven.
"""

from __future__ import annotations

from dataclasses import dataclass

from orccad_app.control.module import PortSpec
from orccad_app.diagnostics import OrccadError, SourceLocation
from orccad_app.lang import ast

__all__ = ["Endpoint", "Connection", "wire"]


@dataclass(frozen=True)
class Endpoint:
    """A component whose ports may be connected: a module or the robot."""

    name: str
    ports: tuple[PortSpec, ...]
    is_robot: bool = False

    @classmethod
    def robot(cls, name: str, robot_type) -> "Endpoint":
        return cls(name, tuple(p.spec for p in robot_type.ports), True)

    def port(self, name: str, loc: SourceLocation) -> PortSpec:
        for port in self.ports:
            if port.name == name:
                return port
        what = "robot" if self.is_robot else "module"
        names = ", ".join(p.name for p in self.ports)
        raise OrccadError(f"{what} '{self.name}' has no port '{name}' (its ports: {names})", loc)


@dataclass(frozen=True)
class Connection:
    """A checked connection ``source.port -> target.port`` with its protocol."""

    source: str
    source_port: str
    target: str
    target_port: str
    protocol: str
    type: str
    dim: int | None
    loc: SourceLocation
    implicit: bool = False

    def __str__(self) -> str:
        return f"{self.source}.{self.source_port} -> {self.target}.{self.target_port}"


def _check_pair(src: PortSpec, dst: PortSpec, text: str, loc: SourceLocation) -> None:
    if src.direction != "out":
        raise OrccadError(f"{text}: '{src.name}' is an input port: a connection starts at an "
                          "output", loc)
    if dst.direction != "in":
        raise OrccadError(f"{text}: '{dst.name}' is an output port: a connection ends at an "
                          "input", loc)
    if src.type != dst.type:
        raise OrccadError(f"{text}: type {src.type} does not match type {dst.type}", loc)
    if src.dim is not None and dst.dim is not None and src.dim != dst.dim:
        raise OrccadError(f"{text}: a vector of {src.dim} cannot feed a vector of {dst.dim}",
                          loc)


def _endpoints(modules: dict, robot: Endpoint) -> dict[str, Endpoint]:
    ends = {name: Endpoint(name, spec.instance.ports) for name, spec in modules.items()}
    ends[robot.name] = robot
    return ends


def _connect(c: ast.Connect, ends: dict[str, Endpoint], fed: dict) -> Connection:
    text = f"connect {c.source.component}.{c.source.port} -> {c.target.component}.{c.target.port}"
    for ref in (c.source, c.target):
        if ref.component not in ends:
            known = ", ".join(ends)
            raise OrccadError(f"{text}: no module or robot '{ref.component}' (known: {known})",
                              ref.loc)
    src = ends[c.source.component].port(c.source.port, c.source.loc)
    dst = ends[c.target.component].port(c.target.port, c.target.loc)
    _check_pair(src, dst, text, c.loc)
    key = (c.target.component, c.target.port)
    if key in fed:
        raise OrccadError(f"{text}: input {key[0]}.{key[1]} is already fed by {fed[key]}", c.loc)
    connection = Connection(c.source.component, src.name, c.target.component, dst.name,
                            c.protocol, src.type, src.dim or dst.dim, c.loc)
    fed[key] = connection
    return connection


def _producer(name: str, ends: dict[str, Endpoint], robot: Endpoint, me: str):
    for end in [robot] + [e for n, e in ends.items() if n not in (robot.name, me)]:
        for port in end.ports:
            if port.name == name and port.direction == "out":
                return end, port
    return None


def _implicit(name: str, spec, ends: dict[str, Endpoint], robot: Endpoint, fed: dict,
              connections: list[Connection]) -> None:
    """Wire a compiler-made module by name: each unfed input reads the robot sensor, else
    the module output, of its source name; each unfed robot actuator of the same name as
    one of its outputs is driven by it."""
    sources = spec.kind.sources(spec.instance.params)
    pairs = []
    for port in spec.instance.ports:
        if port.direction == "in" and (name, port.name) not in fed:
            found = _producer(sources.get(port.name, port.name), ends, robot, name)
            if found is not None:
                pairs.append((found[0].name, found[1], name, port))
        elif port.direction == "out" and (robot.name, port.name) not in fed:
            actuator = next((p for p in robot.ports if p.name == port.name
                             and p.direction == "in"), None)
            if actuator is not None:
                pairs.append((name, port, robot.name, actuator))
    for source, src, target, dst in pairs:
        text = f"{source}.{src.name} -> {target}.{dst.name} (implicit)"
        _check_pair(src, dst, text, spec.loc)
        connection = Connection(source, src.name, target, dst.name, "asyn/asyn", src.type,
                                src.dim or dst.dim, spec.loc, implicit=True)
        fed[(target, dst.name)] = connection
        connections.append(connection)


def _alternatives(spec) -> tuple[frozenset[str], ...]:
    """Sets of inputs of which one must be fed in full for the module ever to compute."""
    inputs = [p for p in spec.instance.ports if p.direction == "in"]
    declared = spec.kind.input_alternatives
    if declared:
        return tuple(frozenset(group) for group in declared)
    if spec.kind.is_observer and inputs and not any(p.required for p in inputs):
        return tuple(frozenset({p.name}) for p in inputs)
    return ()


def _check_inputs(task: ast.RobotTask, modules: dict, fed: dict) -> None:
    for name, spec in modules.items():
        for port in spec.instance.ports:
            if port.direction == "in" and port.required and (name, port.name) not in fed:
                raise OrccadError(f"input {name}.{port.name} of Robot-Task '{task.name}' is not "
                                  f"connected (add 'connect … -> {name}.{port.name};')", spec.loc)
        groups = _alternatives(spec)
        if groups and not any(all((name, p) in fed for p in group) for group in groups):
            needs = ", or ".join(" and ".join(sorted(group)) for group in groups)
            what = "observer" if spec.kind.is_observer else "module"
            raise OrccadError(f"{what} {name} ({spec.kind.name}) of Robot-Task '{task.name}' can "
                              f"never receive its inputs: it needs {needs}, and nothing in the "
                              f"task feeds them (connect them, or give the task a law whose "
                              f"modules produce them)", spec.loc)


def _check_actuators(task: ast.RobotTask, robot: Endpoint, fed: dict) -> None:
    for port in robot.ports:
        if port.direction == "in" and (robot.name, port.name) not in fed:
            raise OrccadError(f"Robot-Task '{task.name}' does not drive {robot.name}.{port.name}: "
                              f"nothing writes the robot's actuator (give the task a 'law', "
                              f"whose default modules drive it, or 'connect … -> "
                              f"{robot.name}.{port.name};')", task.loc)


def wire(task: ast.RobotTask, modules: dict, robot: Endpoint) -> list[Connection]:
    """Check the task's ``connect`` clauses, wire the compiler-made modules (the law's
    defaults, the observers) and check coherence: every required input fed, every module
    able to receive its inputs, every actuator of the robot driven."""
    ends = _endpoints(modules, robot)
    fed: dict[tuple[str, str], Connection] = {}
    connections = [_connect(c, ends, fed) for c in task.connections]
    for name, spec in modules.items():
        if spec.implicit:
            _implicit(name, spec, ends, robot, fed, connections)
    _check_actuators(task, robot, fed)
    _check_inputs(task, modules, fed)
    return connections
