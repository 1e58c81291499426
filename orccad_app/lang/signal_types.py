"""Typing the signal atoms of Signal Temporal Logic properties against the robot types.

A signal expression reads the ports a robot type declares (``auv.depth``, ``arm.q``,
``arm.tau``): a ``float`` port is a scalar, a ``vector`` port of dimension ``n`` a vector
whose components are ``robot.port[0]`` … ``robot.port[n-1]``. ``+ -`` apply to two scalars or
two vectors of one dimension, ``*`` to scalars or a scalar and a vector, ``/`` to a vector or
scalar divided by a scalar; ``norm(v)`` is the Euclidean norm of a vector (or ``abs`` of a
scalar), ``abs`` and ``sqrt`` take scalars. A comparison takes two scalars. Every robot also has ``robot.e``, the task error of the
Robot-Task running on it (:data:`~orccad_app.control.ports.TASK_ERROR`): like a TCS port
it holds its last value between writes and is zero before the first.

Errors carry the location of the offending expression; :func:`check_signal_properties` runs
when a file is loaded, so ``orccad check``, ``compile`` and ``run`` refuse a bad property
alike.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Mapping

from orccad_app.control.ports import TASK_ERROR
from orccad_app.diagnostics import OrccadError
from orccad_app.lang import ast

__all__ = ["PortSignal", "signal_ports", "port_signals", "check_signal_properties",
           "expr_dim", "formula_unit"]


@dataclass(frozen=True)
class PortSignal:
    """A robot port read by signal properties.

    :param robot: the robot's name in the file (``auv``).
    :param port: the port (``depth``).
    :param dim: 0 for a scalar (``float``) port, else the vector's length.
    :param unit: the port's unit as the robot type documents it (``[m]``), ``""`` if none.
    :param actuator: ``True`` for an actuator port (its value is the held command).
    :param task_error: ``True`` for ``robot.e``: the task error written by the control law
        of the Robot-Task running on the robot (see :data:`~orccad_app.control.ports.TASK_ERROR`).
    """

    robot: str
    port: str
    dim: int
    unit: str = ""
    actuator: bool = False
    task_error: bool = False


def _exprs(formula: ast.Formula):
    for node in ast.formula_nodes(formula):
        if isinstance(node, ast.FCompare):
            yield node.left
            yield node.right


def _ports_of(expr: ast.SignalExpr):
    if isinstance(expr, ast.SPort):
        yield expr
    elif isinstance(expr, ast.SCall):
        for arg in expr.args:
            yield from _ports_of(arg)
    elif isinstance(expr, ast.SNeg):
        yield from _ports_of(expr.operand)
    elif isinstance(expr, ast.SArith):
        yield from _ports_of(expr.left)
        yield from _ports_of(expr.right)


def signal_ports(formula: ast.Formula) -> list[ast.SPort]:
    """Every port reference in the signal atoms of ``formula``, in order."""
    return [port for expr in _exprs(formula) for port in _ports_of(expr)]


def _port_signal(ref: ast.SPort, robot_types: Mapping[str, Any]) -> PortSignal:
    robot_type = robot_types.get(ref.robot)
    if robot_type is None:
        raise OrccadError(f"unknown robot '{ref.robot}' (robots: "
                          f"{', '.join(sorted(robot_types)) or 'none declared'})", ref.loc)
    for port in robot_type.ports:
        if port.name == ref.port:
            dim = 0 if port.spec.type == "float" else len(port.mj_names)
            return PortSignal(ref.robot, ref.port, dim, port.unit,
                              port.spec.direction == "in")
    if ref.port == TASK_ERROR:
        return PortSignal(ref.robot, ref.port, robot_type.dof, task_error=True)
    names = ", ".join([port.name for port in robot_type.ports] + [TASK_ERROR])
    raise OrccadError(f"robot '{ref.robot}' (type {robot_type.name}) has no port "
                      f"'{ref.port}'; its ports: {names}", ref.loc)


def port_signals(formula: ast.Formula, robot_types: Mapping[str, Any]) -> dict[
        tuple[str, str], PortSignal]:
    """The ports ``formula`` reads, keyed ``(robot, port)``, after typing every signal
    expression; raises a located :class:`OrccadError`. ``robot_types`` maps the file's
    robot names to their (configured) robot types."""
    found: dict[tuple[str, str], PortSignal] = {}
    for ref in signal_ports(formula):
        found.setdefault((ref.robot, ref.port), _port_signal(ref, robot_types))
    for node in ast.formula_nodes(formula):
        if isinstance(node, ast.FCompare):
            for side in (node.left, node.right):
                if expr_dim(side, found):
                    raise OrccadError(f"'{node.op}' compares scalars; this side is a vector "
                                      f"of {expr_dim(side, found)} components: compare a "
                                      "component (robot.port[i]) or its norm(...)", side.loc)
    return found


def expr_dim(expr: ast.SignalExpr, ports: Mapping[tuple[str, str], PortSignal]) -> int:
    """0 for a scalar expression, else the length of the vector; raises on a type error."""
    if isinstance(expr, ast.SNumber):
        return 0
    if isinstance(expr, ast.SPort):
        dim = ports[(expr.robot, expr.port)].dim
        if expr.index is None:
            return dim
        if not dim:
            raise OrccadError(f"{expr.robot}.{expr.port} is a scalar: it has no component "
                              f"[{expr.index}]", expr.loc)
        if expr.index >= dim:
            raise OrccadError(f"{expr.robot}.{expr.port} has {dim} components "
                              f"([0] to [{dim - 1}]), not [{expr.index}]", expr.loc)
        return 0
    if isinstance(expr, ast.SNeg):
        return expr_dim(expr.operand, ports)
    if isinstance(expr, ast.SCall):
        dims = [expr_dim(arg, ports) for arg in expr.args]
        if expr.func != "norm" and any(dims):
            raise OrccadError(f"{expr.func}() takes a scalar, got a vector of {max(dims)} "
                              "components (norm() takes a vector)", expr.loc)
        return 0
    left, right = expr_dim(expr.left, ports), expr_dim(expr.right, ports)
    return _arith_dim(expr, left, right)


def _arith_dim(expr: ast.SArith, left: int, right: int) -> int:
    if expr.op in "+-":
        if left != right:
            raise OrccadError(f"'{expr.op}' needs two scalars or two vectors of one length, "
                              f"got {_shape(left)} and {_shape(right)}", expr.loc)
        return left
    if expr.op == "*" and left and right:
        raise OrccadError("'*' of two vectors: write the components", expr.loc)
    if expr.op == "/" and right:
        raise OrccadError("'/' by a vector", expr.loc)
    return max(left, right)


def _shape(dim: int) -> str:
    return "a scalar" if not dim else f"a vector of {dim}"


def formula_unit(ports: Mapping[tuple[str, str], PortSignal]) -> str:
    """The unit of a property's robustness: its ports' unit when they share one, else
    ``""`` (a property mixing metres and percent has a robustness in mixed units)."""
    units = {port.unit for port in ports.values()}
    return units.pop() if len(units) == 1 else ""


def check_signal_properties(program: ast.Program, host: Any) -> None:
    """Type every signal property of ``program`` against the robot types of its robots
    (``host.robot_types``); raise a located :class:`OrccadError` on the first problem."""
    signal = [p for p in program.properties if ast.is_signal_formula(p.formula)]
    if not signal:
        return
    robot_types = {}
    for robot in program.robots:
        try:
            robot_types[robot.name] = host.robot_types.get(robot.type)
        except Exception as error:  # noqa: BLE001 - reported with the robot's location
            raise OrccadError(str(error), robot.loc) from None
    for prop in signal:
        port_signals(prop.formula, robot_types)
