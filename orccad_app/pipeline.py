"""The compiler pipeline shared by the CLI and the TUI: read → parse → check → lower → compile.

Each step is a function over immutable data, so each is testable alone; this module only
chains them and picks the mission a command is about.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from orccad_app.diagnostics import OrccadError
from orccad_app.lang import ast
from orccad_app.lang.names import check
from orccad_app.lang.parser import parse
from orccad_app.plugin_host.host import PluginHost
from orccad_app.reactive.automaton import Automaton
from orccad_app.reactive.compiler import DEFAULT_MAX_STATES, compile_program
from orccad_app.reactive.lower import lower_mission
from orccad_app.robottask.application import ABSTRACT, COMPOSED, AbstractApplicationLowerer
from orccad_app.robottask.composition import Composition, compose
from orccad_app.robottask.model import RobotTaskInstance, TaskInstances, check_tasks

__all__ = ["Source", "load", "select_mission", "compile_mission", "compose_mission",
           "COMPOSED", "ABSTRACT"]


@dataclass(frozen=True)
class Source:
    """A parsed and checked ``.orc`` file.

    :param path: the file's path.
    :param text: its text.
    :param program: its checked AST.
    :param warnings: the checker's warnings.
    :param instances: the checked Robot-Task instances (one per ``run`` site).
    :param host: the plugin host the Robot-Tasks were checked against (``None`` when the file
        declares none).
    """

    path: str
    text: str
    program: ast.Program
    warnings: tuple = ()
    instances: TaskInstances = field(default_factory=lambda: TaskInstances({}, {}))
    host: PluginHost | None = None

    def instance(self, run: ast.Run) -> RobotTaskInstance:
        """The checked Robot-Task instance of the ``run`` statement ``run``."""
        return self.instances.by_run[run.loc]

    def print_warnings(self, stream=None) -> None:
        """Print the checker's warnings (``file:line:col: warning: …``) to ``stream``."""
        import sys
        for warning in self.warnings:
            print(warning.format(self.text), file=stream or sys.stderr)


def load(path: str | Path, host: PluginHost | None = None) -> Source:
    """Read, parse and check ``path``; errors are :class:`OrccadError` with locations.

    The Robot-Tasks are checked against ``host``'s registries; without one, and when the file
    declares Robot-Tasks, the installed plugins are loaded (:meth:`PluginHost.load`) and
    their failures printed once on stderr."""
    path = str(path)
    try:
        text = Path(path).read_text(encoding="utf-8")
    except FileNotFoundError:
        raise OrccadError(f"{path}: no such file") from None
    except (OSError, UnicodeDecodeError) as error:
        raise OrccadError(f"{path}: cannot read: {error}") from None
    program = parse(text, path)
    result = check(program)
    instances = TaskInstances({}, {})
    if program.robottasks:
        if host is None:
            host = PluginHost.load()
            host.warn_failures()
        instances = check_tasks(program, host)
    return Source(path, text, program, result.warnings, instances, host)


def select_mission(source: Source, name: str | None) -> ast.Mission:
    """The mission called ``name``, or the file's only mission when ``name`` is None."""
    missions = source.program.missions
    if name is not None:
        mission = source.program.mission(name)
        if mission is None:
            known = ", ".join(m.name for m in missions) or "none"
            raise OrccadError(f"{source.path}: no mission named '{name}' (missions: {known})")
        return mission
    if not missions:
        raise OrccadError(f"{source.path}: the file declares no mission")
    if len(missions) > 1:
        names = ", ".join(m.name for m in missions)
        raise OrccadError(f"{source.path}: several missions ({names}); choose one with --mission")
    return missions[0]


def compile_mission(source: Source, mission: ast.Mission, *, view: str = COMPOSED,
                    max_states: int = DEFAULT_MAX_STATES) -> Automaton:
    """The minimized automaton of ``mission``.

    ``view`` is ``composed`` (the application automaton with the RTAs of its Robot-Tasks
    inlined: what is checked and run) or ``abstract`` (Robot-Tasks seen through their start
    and outcome signals: what ``orccad react`` drives). See :mod:`orccad_app.robottask.application`.
    """
    if view == ABSTRACT:
        program = lower_mission(source.program, mission, AbstractApplicationLowerer)
        return compile_program(program, max_states=max_states)
    return compose_mission(source, mission, max_states=max_states).automaton


def compose_mission(source: Source, mission: ast.Mission, *,
                    max_states: int = DEFAULT_MAX_STATES) -> Composition:
    """The composed automaton of ``mission`` with its ``run`` sites and signal roles (what the
    checker and the mission layer start from)."""
    return compose(source.program, mission, max_states=max_states)
