"""Connections of a Robot-Task's Module-Tasks, checked (RR-1801 §3.2).

``connect a.b -> c.d : protocol`` joins one producer port to one consumer port. Checked:
both ends exist (a module of the task or its robot), the source is an output and the target
an input, types and vector dimensions agree, each input is fed once, and every required
input is fed. Observers that the compiler instantiated (named in ``from`` or in a condition)
are wired implicitly: each input reads the robot sensor of the same name, else the module
output of that name (``q`` from ``arm.q``, ``e`` from the control law).
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


def wire(task: ast.RobotTask, modules: dict, robot: Endpoint) -> list[Connection]:
    """Check the task's ``connect`` clauses and wire its implicit observers."""
    ends = _endpoints(modules, robot)
    fed: dict[tuple[str, str], Connection] = {}
    connections = [_connect(c, ends, fed) for c in task.connections]
    for name, spec in modules.items():
        if not spec.implicit:
            continue
        sources = spec.kind.sources(spec.instance.params)
        for port in spec.instance.ports:
            if port.direction != "in" or (name, port.name) in fed:
                continue
            found = _producer(sources.get(port.name, port.name), ends, robot, name)
            if found is None:
                continue
            end, src = found
            text = f"{end.name}.{src.name} -> {name}.{port.name} (implicit)"
            _check_pair(src, port, text, spec.loc)
            connection = Connection(end.name, src.name, name, port.name, "asyn/asyn", src.type,
                                    src.dim or port.dim, spec.loc, implicit=True)
            fed[(name, port.name)] = connection
            connections.append(connection)
    for name, spec in modules.items():
        for port in spec.instance.ports:
            if port.direction == "in" and port.required and (name, port.name) not in fed:
                raise OrccadError(f"input {name}.{port.name} of Robot-Task '{task.name}' is not "
                                  f"connected (add 'connect … -> {name}.{port.name};')", spec.loc)
    return connections
