"""``orccad plugins``: what the installed plugins provide, and from which plugin.

Lists the loaded plugins, then robot types, control laws, task functions, trajectories,
observers and module kinds with their providing plugin and a one-line summary.
``--verbose`` adds parameters, ports, default timing and, for module kinds and observers,
where their C is (the runtime library's, the plugin's file, or none: Python only; ``c`` in
the JSON); ``--json`` prints one JSON document. Plugins that failed are reported on stderr (``warning: plugin 'x' disabled: …``)
and the listing still shows what the others provide.
"""

from __future__ import annotations

import argparse
from typing import Any

#: The environment variable naming plugins to disable (``plugin_host.host.DISABLE_ENV``; a test
#: keeps them equal: importing the host here would load numpy for every command).
DISABLE_ENV = "ORCCAD_DISABLE_PLUGINS"

__all__ = ["register", "run", "describe"]

#: (registry attribute, heading) in listing order.
SECTIONS: tuple[tuple[str, str], ...] = (
    ("robot_types", "robot types"),
    ("control_laws", "control laws"),
    ("task_functions", "task functions"),
    ("trajectories", "trajectories"),
    ("observers", "observers"),
    ("module_kinds", "module kinds"),
)


def register(subparsers: Any) -> None:
    """Add the ``plugins`` sub-command."""
    parser = subparsers.add_parser(
        "plugins", help="list what the installed plugins provide",
        description="List robot types, control laws, task functions, trajectories, "
                    f"observers and module kinds with their plugin. {DISABLE_ENV}=a,b "
                    "disables the named plugins.")
    parser.add_argument("--json", action="store_true", help="print JSON")
    parser.add_argument("-v", "--verbose", action="store_true",
                        help="also list parameters, ports, timing and which kinds have C")
    parser.set_defaults(func=run)


def _params(params: Any) -> list[dict[str, Any]]:
    return [{"name": p.name, "type": p.type, "required": p.required,
             "default": None if p.required else _plain(p.default), "doc": p.doc,
             "minimum": p.minimum, "exclusive": p.exclusive, "maximum": p.maximum}
            for p in params]


def _range(param: dict[str, Any]) -> str:
    """`` in [0, 0.1]``, `` > 0``… (empty without bounds)."""
    low, high = param.get("minimum"), param.get("maximum")
    if low is None and high is None:
        return ""
    if high is None:
        return f"  {'>' if param.get('exclusive') else '>='} {low:g}"
    if low is None:
        return f"  <= {high:g}"
    return f"  in {'(' if param.get('exclusive') else '['}{low:g}, {high:g}]"


def _plain(value: Any) -> Any:
    if hasattr(value, "tolist"):
        return value.tolist()
    return value


def _ports(ports: Any) -> list[dict[str, Any]]:
    return [{"name": p.name, "direction": p.direction, "type": p.type, "dim": p.dim,
             "required": p.required, "doc": p.doc} for p in ports]


def _item(category: str, item: Any) -> dict[str, Any]:
    """The JSON description of one registered item."""
    info: dict[str, Any] = {"summary": getattr(item, "summary", "")}
    info["params"] = _params(getattr(item, "parameters" if category == "robot_types"
                                     else "params", ()))
    if category == "robot_types":
        low, high = item.torque_limits
        info.update(mjcf=str(item.mjcf_path), dof=item.dof, resources=list(item.resources),
                    ports=_ports(port.spec for port in item.ports),
                    torque_limits=[low.tolist(), high.tolist()],
                    joint_limits=[_plain(limit) for limit in item.joint_limits],
                    end_effector=item.end_effector)
    elif category in ("observers", "module_kinds"):
        from orccad_app.sil.generate.layout import kind_c

        timing = item.default_timing
        info.update(ports=_ports(item.ports), default_timing={
            "period_ns": timing.period_ns, "wcet_ns": timing.wcet_ns, "bcet_ns": timing.bcet_ns},
            c=kind_c(item))
    return info


def describe(host: Any) -> dict[str, Any]:
    """Everything ``orccad plugins --json`` prints."""
    document: dict[str, Any] = {"plugins": [vars(info) for info in host.plugins.values()]}
    for category, _ in SECTIONS:
        registry = getattr(host.registries, category)
        document[category] = [{"name": e.name, "plugin": e.plugin, **_item(category, e.item)}
                              for e in registry.entries()]
    document["failures"] = [vars(failure) for failure in host.failures]
    document["blocked"] = sorted(host.blocked)
    return document


def _text(document: dict[str, Any], verbose: bool) -> str:
    lines = ["plugins:"]
    for info in document["plugins"]:
        origin = f"{info['distribution']} {info['version']}" if info["distribution"] else "-"
        lines.append(f"  {info['name']:<24} {origin:<20} module {info['module']}")
    if document["blocked"]:
        lines.append(f"  (disabled by {DISABLE_ENV}: {', '.join(document['blocked'])})")
    for category, heading in SECTIONS:
        entries = document[category]
        lines.append(f"{heading}:" if entries else f"{heading}: none")
        for entry in entries:
            lines.append(f"  {entry['name']:<20} {entry['plugin']:<20} {entry['summary']}")
            if verbose:
                lines.extend(_details(entry))
    return "\n".join(lines)


def _details(entry: dict[str, Any]) -> list[str]:
    lines = []
    for param in entry["params"]:
        default = "required" if param["required"] else f"= {param['default']!r}"
        lines.append(f"      param {param['name']}: {param['type']} {default}{_range(param)}  "
                     f"{param['doc']}")
    for port in entry.get("ports", ()):
        dim = f"[{port['dim']}]" if port["dim"] else ""
        optional = "" if port["required"] else " (optional)"
        lines.append(f"      port  {port['direction']:<3} {port['name']}: {port['type']}{dim}"
                     f"{optional}  {port['doc']}")
    timing = entry.get("default_timing")
    if timing:
        lines.append(f"      timing period {timing['period_ns'] / 1e6:g} ms, "
                     f"wcet {timing['wcet_ns'] / 1e6:g} ms")
    if "c" in entry:
        where = entry["c"] or "none: Python only (orccad sil and codegen --module-tasks refuse it)"
        lines.append(f"      C     {where}")
    if "mjcf" in entry:
        lines.append(f"      mjcf  {entry['mjcf']}")
    return lines


def run(args: argparse.Namespace) -> int:
    """Print the listing; failed plugins are warnings on stderr (exit status stays 0)."""
    from orccad_app.jsonout import dumps
    from orccad_app.plugin_host import PluginHost

    host = PluginHost.load()
    host.warn_failures()
    document = describe(host)
    if args.json:
        print(dumps(document, indent=2))
    else:
        print(_text(document, args.verbose))
    return 0
