"""Hover: what the name under the cursor is, in Markdown.

- a Robot-Task: its signature (parameters, types, defaults), robot, duration, law, task
  function, and its Module-Tasks with period, WCET, processor and priority (as instantiated,
  the law's default modules and timing included, when the file passed its checks);
- a law, trajectory, task function, observer, module kind or robot type (a name of the
  plugin registries): its summary and parameters with their units, defaults and ranges;
- a signal: direction, type, where it is declared and its role (tested, emitted, a
  Robot-Task's pre- or post-condition);
- an exception: its type (1, 2 or 3), what raises it and where it is caught;
- a property: its formula's mission and its last verdict in this editor;
- a mission, robot, variable, parameter, Module-Task, trap: its declaration.
"""

from __future__ import annotations

from typing import Any, Callable

from orccad_app.diagnostics import value_text
from orccad_app.lang import ast
from orccad_app.lang.walk import nodes
from orccad_app.lsp.index import Declaration, DeclKind

__all__ = ["hover_declaration", "hover_registry", "expr_text", "REGISTRIES", "Verdicts"]

#: The plugin registries a name may come from: attribute of the host, and what to call it.
REGISTRIES = (("control_laws", "control law"), ("task_functions", "task function"),
              ("trajectories", "trajectory"), ("observers", "observer"),
              ("module_kinds", "module kind"), ("robot_types", "robot type"))

#: ``(mission, property) -> verdict text`` (``None``: not judged yet).
Verdicts = Callable[[str | None, str], "str | None"]


def _ns(value: int | None) -> str:
    if value is None:
        return "default"
    for unit, scale in (("s", 10**9), ("ms", 10**6), ("us", 10**3)):
        if value >= scale:
            return f"{value / scale:g} {unit}"
    return f"{value} ns"


def expr_text(expr: Any) -> str:
    """An expression as written (literals and names; the rest by its kind)."""
    if expr is None:
        return ""
    for attribute in ("text", "name"):
        text = getattr(expr, attribute, None)
        if isinstance(text, str) and text:
            return text
    if isinstance(expr, ast.Vector):
        return "[" + ", ".join(expr_text(i) for i in expr.items) + "]"
    value = getattr(expr, "value", None)
    if value is not None:
        return value_text(value)
    if isinstance(expr, ast.Unary):
        return f"{expr.op}{expr_text(expr.operand)}"
    if isinstance(expr, ast.Binary):
        return f"{expr_text(expr.left)} {expr.op} {expr_text(expr.right)}"
    if isinstance(expr, ast.Call):
        return f"{expr.func}({', '.join(_arg(a) for a in expr.args)})"
    return "…"


def _arg(arg: ast.Arg) -> str:
    return f"{arg.name} = {expr_text(arg.value)}" if arg.name else expr_text(arg.value)


def _call(call: ast.Call | None) -> str:
    return "—" if call is None else f"`{call.func}({', '.join(_arg(a) for a in call.args)})`"


def _signature(task: ast.RobotTask) -> str:
    params = ", ".join(p.name + (f": {p.type}" if p.type else "")
                       + (f" = {expr_text(p.default)}" if p.default is not None else "")
                       for p in task.params)
    return f"robottask {task.name}({params}) on {task.robot}"


def hover_declaration(decl: Declaration, program: ast.Program, source: Any,
                      verdicts: Verdicts) -> str:
    """The Markdown of a hover on ``decl`` (``source``: the checked file, or ``None``)."""
    node = decl.node
    if decl.kind is DeclKind.ROBOTTASK:
        return _robottask(node, source)
    if decl.kind is DeclKind.SIGNAL:
        return _signal(decl, program)
    if decl.kind is DeclKind.EXCEPTION:
        return _exception(decl, program)
    if decl.kind is DeclKind.PROPERTY:
        verdict = verdicts(node.mission, node.name) or \
            "not judged yet: save the file (or run the command `orccad.check`)"
        where = f"{node.mission}." if node.mission else ""
        return f"```orccad\nproperty {where}{node.name}\n```\nlast verdict: **{verdict}**"
    if decl.kind is DeclKind.MISSION:
        signature = ", ".join(f"{s.direction.value} {s.name}" for s in node.signature)
        signals = ", ".join(f"{s.direction.value} {s.name}" + (f" : {s.type}" if s.type else "")
                            for s in node.signals)
        runs = sorted({n.task for n in nodes(node) if isinstance(n, ast.Run)})
        text = f"```orccad\nmission {node.name}" + (f" [{signature}]" if signature else "") \
            + "\n```"
        if signals:
            text += f"\nsignals: {signals}"
        if runs:
            text += f"\n\nruns: {', '.join(runs)}"
        return text + f"\n\ndeclared in {node.loc.file}:{node.loc.line}"
    if decl.kind is DeclKind.ROBOT:
        args = ", ".join(_arg(a) for a in node.args)
        return f"```orccad\nrobot {node.name} : {node.type}" + (f"({args})" if args else "") \
            + "\n```"
    if decl.kind is DeclKind.MODULE:
        return (f"```orccad\nmodule {node.name} : {node.kind}\n```\n"
                + _module_line(node.name, node.kind, node.period_ns, node.wcet_ns,
                               node.processor, node.priority))
    if decl.kind is DeclKind.PARAMETER:
        default = f" = {expr_text(node.default)}" if node.default is not None else ""
        return f"parameter of Robot-Task {decl.owner}: `{node.name}: {node.type}{default}`"
    if decl.kind is DeclKind.VARIABLE:
        return f"variable of mission {decl.owner}: `var {node.name} := {expr_text(node.value)}`"
    return f"trap `{node.name}` of mission {decl.owner}: `exit {node.name}` leaves it"


def _module_line(name: str, kind: str, period_ns, wcet_ns, processor, priority) -> str:
    return (f"| {name} | {kind} | {_ns(period_ns)} | {_ns(wcet_ns)} | {processor or 'default'} "
            f"| {priority if priority is not None else 'default'} |")


_TABLE = "| Module-Task | kind | period | WCET | processor | priority |\n|---|---|---|---|---|---|"


def _robottask(task: ast.RobotTask, source: Any) -> str:
    lines = [f"```orccad\n{_signature(task)}\n```",
             f"duration {_ns(task.duration_ns) if task.duration_ns else 'none (ends on its post-condition)'}; "
             f"law {_call(task.law)}; task function {_call(task.task_function)}", "", _TABLE]
    instance = None
    if source is not None and source.tasks is not None:
        instance = source.tasks.defaults.get(task.name) or next(
            (i for i in source.tasks.by_run.values() if i.task.name == task.name), None)
    if instance is not None:
        for spec in instance.modules.values():
            lines.append(_module_line(spec.name, spec.kind.name, spec.timing.period_ns,
                                      spec.timing.wcet_ns, spec.processor, spec.priority))
    else:
        lines += [_module_line(m.name, m.kind, m.period_ns, m.wcet_ns, m.processor, m.priority)
                  for m in task.modules]
    if task.exceptions:
        lines += ["", "exceptions: " + ", ".join(
            f"{e.name} (type {e.type.number}, {e.type.value})" for e in task.exceptions)]
    return "\n".join(lines)


def _signal(decl: Declaration, program: ast.Program) -> str:
    node: ast.SignalDecl = decl.node
    kind = "local signal" if node.direction not in (ast.Direction.INPUT, ast.Direction.OUTPUT) \
        else node.direction.value
    typed = f" : {node.type}" if node.type else " (pure)"
    where = f"mission {decl.owner}" if decl.owner else "the file (every mission)"
    roles = []
    for task in program.robottasks:
        if any(isinstance(p, ast.SignalPrecondition) and p.signal == node.name
               for p in task.preconditions):
            roles.append(f"synchronization pre-condition of Robot-Task {task.name}")
        if any(isinstance(p, ast.SignalPostcondition) and p.signal == node.name
               for p in task.postconditions):
            roles.append(f"post-condition emitted by Robot-Task {task.name}")
    scope = program.mission(decl.owner) if decl.owner else None
    emitted = tested = 0
    for mission in [scope] if scope is not None else program.missions:
        for n in nodes(mission):
            if isinstance(n, (ast.Emit, ast.Sustain)) and n.signal == node.name:
                emitted += 1
            elif isinstance(n, (ast.Name, ast.LastValue, ast.PreSignal)) \
                    and getattr(n, "name", getattr(n, "signal", None)) == node.name:
                tested += 1
    if emitted:
        roles.append(f"emitted at {emitted} place{'s' if emitted > 1 else ''}")
    if tested:
        roles.append(f"tested or read at {tested} place{'s' if tested > 1 else ''}")
    if node.direction is ast.Direction.INPUT:
        roles.insert(0, "from the environment or the operator (`--inject`, a react script)")
    text = f"```orccad\n{kind} {node.name}{typed}\n```\ndeclared in {where}"
    if node.combine:
        text += f"; emissions of an instant combine with `{node.combine}`"
    return text + ("\n\n" + "; ".join(roles) if roles else "")


def _exception(decl: Declaration, program: ast.Program) -> str:
    node: ast.ExceptionDecl = decl.node
    task = program.robottask(decl.owner) if decl.owner else None
    source = node.source
    module = task.module(source.func) if task is not None else None
    raiser = (f"Module-Task `{module.name}` ({module.kind})" if module is not None
              else f"observer {_call(source)}")
    meaning = {1: f"type 1: the Robot-Task goes on, `{_adjust(node)}`",
               2: "type 2: the Robot-Task is killed and `run` raises it in the mission "
                  "(a `try … catch` handles it)",
               3: "type 3: fatal, the Robot-Task and the whole mission are aborted "
                  "(`on fatal` runs)"}[node.type.number]
    caught = sum(1 for n in nodes(program) if isinstance(n, ast.Catch)
                 and node.name in n.exceptions)
    text = (f"```orccad\nexception {node.name} : {node.type.value}\n```\n"
            f"of Robot-Task {decl.owner}, raised by {raiser}\n\n{meaning}")
    if caught:
        text += f"\n\ncaught by {caught} `catch`{'es' if caught > 1 else ''}"
    return text


def _adjust(node: ast.ExceptionDecl) -> str:
    adjust = node.adjust
    if adjust is None:
        return "adjust"
    return f"adjust {adjust.target.component}.{adjust.target.port} = {expr_text(adjust.value)}"


def hover_registry(name: str, host: Any) -> str | None:
    """The Markdown of a hover on a name of the plugin registries, or ``None``."""
    if host is None:
        return None
    for attribute, what in REGISTRIES:
        entry = getattr(host, attribute).get(name)
        if entry is None:
            continue
        text = f"**{what}** `{name}` — {getattr(entry, 'summary', '')}"
        try:
            provider = host.provider(attribute, name)
            text += f" (plugin `{provider}`)"
        except Exception:  # noqa: BLE001 - the provider is a nicety
            pass
        params = tuple(getattr(entry, "params", ()) or ())
        if params:
            text += "\n\n| parameter | type | default | range | meaning |\n|---|---|---|---|---|"
            for spec in params:
                cells = (f"`{spec.name}`", str(spec.type), _default(spec), _range(spec),
                         str(spec.doc))
                text += "\n| " + " | ".join(c.replace("|", "\\|") for c in cells) + " |"
        return text
    return None


def _default(spec: Any) -> str:
    if getattr(spec, "required", False):
        return "required"
    return "—" if spec.default is None else f"`{value_text(spec.default)}`"


def _range(spec: Any) -> str:
    if spec.choices:
        return "one of " + ", ".join(f"`{c}`" for c in spec.choices)
    low, high = spec.minimum, spec.maximum
    if low is None and high is None:
        return "—"
    left = "(" if spec.exclusive or low is None else "["
    right = ")" if high is None else "]"
    return f"{left}{'-∞' if low is None else f'{low:g}'}, {'∞' if high is None else f'{high:g}'}{right}"
