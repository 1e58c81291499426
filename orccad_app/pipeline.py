"""The compiler pipeline shared by the CLI and the TUI: read → parse → check → lower → compile.

Each step is a function over immutable data, so each is testable alone; this module only
chains them and picks the mission a command is about.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Callable

from orccad_app.diagnostics import OrccadError, SourceLocation
from orccad_app.lang import ast
from orccad_app.lang.imports import ImportedFile, resolve_imports
from orccad_app.lang.names import check
from orccad_app.lang.parser import parse
from orccad_app.reactive.automaton import Automaton
from orccad_app.reactive.compiler import DEFAULT_MAX_STATES, compile_program
from orccad_app.reactive.lazy import LazyAutomaton
from orccad_app.reactive.lower import lower_mission
from orccad_app.robottask.application import ABSTRACT, COMPOSED, AbstractApplicationLowerer
from orccad_app.robottask.composition import Composition, compose

if TYPE_CHECKING:  # the model imports the control layer (numpy): only when a file has tasks
    from orccad_app.plugin_host.host import PluginHost
    from orccad_app.robottask.model import RobotTaskInstance, TaskInstances

__all__ = ["require_regular_file", "Source", "load", "check_source", "read_source",
           "MAX_SOURCE_BYTES", "select_mission", "require_missions", "compile_mission",
           "compose_mission",
           "COMPOSED", "ABSTRACT"]


@dataclass(frozen=True)
class Source:
    """A parsed and checked ``.orc`` file.

    :param path: the file's path.
    :param text: its text.
    :param program: its checked AST.
    :param warnings: the checker's warnings.
    :param tasks: the checked Robot-Task instances (one per ``run`` site), ``None`` for a file
        without Robot-Tasks (see :attr:`instances`).
    :param host: the plugin host the file was checked against (``None`` when it needed none).
    :param imported: the files its ``import`` declarations loaded, in load order.
    """

    path: str
    text: str
    program: ast.Program
    warnings: tuple = ()
    tasks: TaskInstances | None = None
    host: PluginHost | None = None
    imported: tuple[ImportedFile, ...] = ()

    @property
    def digest(self) -> str:
        """SHA-256 of the program's text: the file's and every imported file's (a change in a
        library changes it)."""
        import hashlib

        digest = hashlib.sha256(self.text.encode())
        for file in self.imported:
            digest.update(f"\0{len(file.text)}\0".encode())
            digest.update(file.text.encode())
        return digest.hexdigest()

    @property
    def instances(self) -> TaskInstances:
        """The checked Robot-Task instances (empty for a file without Robot-Tasks)."""
        if self.tasks is None:
            from orccad_app.robottask.model import TaskInstances
            return TaskInstances({}, {})
        return self.tasks

    def instance(self, run: ast.Run) -> RobotTaskInstance:
        """The checked Robot-Task instance of the ``run`` statement ``run``."""
        return self.instances.by_run[run.loc]

    def print_warnings(self, stream=None) -> None:
        """Print the checker's warnings (``file:line:col: warning: …``) to ``stream``."""
        import sys
        for warning in self.warnings:
            print(warning.format(self.text), file=stream or sys.stderr)


def load(path: str | Path, host: PluginHost | None = None, text: str | None = None,
         read: Callable[[str], str] | None = None) -> Source:
    """Read, parse and check ``path`` (or ``text``, an edited version of it: its imports are
    still resolved from ``path``'s folder); errors are :class:`OrccadError` with locations.
    ``read(path)`` gives the text of an imported file (default :func:`read_source`: the disk;
    the language server passes one that prefers the editor's unsaved buffers).

    The Robot-Tasks are checked against ``host``'s registries; without one, and when the file
    declares Robot-Tasks, the installed plugins are loaded (:meth:`PluginHost.load`) and
    their failures printed once on stderr."""
    path = str(path)
    text = read_source(path) if text is None else text
    return check_source(path, text, parse(text, path), host, read)


def check_source(path: str, text: str, parsed: ast.Program, host: PluginHost | None = None,
                 read: Callable[[str], str] | None = None) -> Source:
    """The steps of :func:`load` after parsing: ``parsed`` (the AST of ``text``) with its
    imports resolved, names checked and Robot-Tasks instantiated (for a caller that keeps
    the parsed AST even when the checks fail, as the language server does)."""
    program, imported = resolve_imports(parsed, read or read_source)
    result = check(program)
    instances = None
    if program.robottasks:
        from orccad_app.robottask.model import check_tasks
        host = _plugins(host)
        instances = check_tasks(program, host)
    if any(ast.is_signal_formula(p.formula) for p in program.properties):
        from orccad_app.lang.signal_types import check_signal_properties
        host = _plugins(host)
        check_signal_properties(program, host)
    return Source(path, text, program, result.warnings, instances, host, imported)


def _plugins(host: PluginHost | None) -> PluginHost:
    """``host``, or the installed plugins loaded now (their failures printed once on stderr):
    only files that need the registries load them."""
    if host is not None:
        return host
    from orccad_app.plugin_host.host import PluginHost
    loaded = PluginHost.load()
    loaded.warn_failures()
    return loaded


#: Largest source file or script read [bytes] (a budget: see docs/limits.md).
MAX_SOURCE_BYTES = 512_000


def require_regular_file(path: str | Path) -> None:
    """Refuse what is not a regular file before opening it: opening a FIFO blocks until a
    writer comes, and a device (``/dev/zero``) or a socket never ends."""
    import stat

    try:
        mode = os.stat(path).st_mode
    except FileNotFoundError:
        raise OrccadError(f"{path}: no such file") from None
    except OSError as error:
        raise OrccadError(f"{path}: cannot read: {error.strerror or error}") from None
    if stat.S_ISDIR(mode):
        raise OrccadError(f"{path}: is a folder, not a file")
    if not stat.S_ISREG(mode):
        kind = "a FIFO" if stat.S_ISFIFO(mode) else "a device" if \
            stat.S_ISCHR(mode) or stat.S_ISBLK(mode) else "a socket" if stat.S_ISSOCK(mode) \
            else "not a regular file"
        raise OrccadError(f"{path}: {kind}, not a regular file (only regular files are read)")


def read_source(path: str | bytes, name: str | None = None) -> str:
    """The text of the file ``path`` (or of the bytes ``path``, called ``name``): UTF-8, an
    optional byte-order mark dropped; errors are located :class:`OrccadError`."""
    if isinstance(path, bytes):
        data, name = path, name or "<input>"
    else:
        name = str(path)
        require_regular_file(path)
        try:
            with open(path, "rb") as handle:
                data = handle.read(MAX_SOURCE_BYTES + 1)
        except FileNotFoundError:
            raise OrccadError(f"{path}: no such file") from None
        except IsADirectoryError:
            raise OrccadError(f"{path}: is a folder, not a file") from None
        except OSError as error:
            raise OrccadError(f"{path}: cannot read: {error.strerror or error}") from None
    if len(data) > MAX_SOURCE_BYTES:
        raise OrccadError(f"{name}: larger than the {MAX_SOURCE_BYTES} bytes an input "
                          "may have")
    if data.startswith(b"\xef\xbb\xbf"):
        data = data[3:]
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as error:
        line = data.count(b"\n", 0, error.start) + 1
        start = data.rfind(b"\n", 0, error.start) + 1
        col = len(data[start:error.start].decode("utf-8", "replace")) + 1
        raise OrccadError(f"not UTF-8 text: byte 0x{data[error.start]:02x} cannot be decoded "
                          "(save the file as UTF-8)", SourceLocation(name, line, col)) from None


def select_mission(source: Source, name: str | None) -> ast.Mission:
    """The mission called ``name``, or the file's only mission when ``name`` is None."""
    missions = source.program.missions
    if name is not None:
        mission = source.program.mission(name)
        if mission is None:
            known = ", ".join(m.name for m in missions) or "none"
            raise OrccadError(f"{source.path}: no mission named '{name}' (missions: {known})")
        return mission
    require_missions(source)
    if len(missions) > 1:
        names = ", ".join(m.name for m in missions)
        raise OrccadError(f"{source.path}: several missions ({names}); choose one with --mission")
    return missions[0]


def require_missions(source: Source) -> tuple[ast.Mission, ...]:
    """The file's missions; a located error when it declares none."""
    if source.program.missions:
        return tuple(source.program.missions)
    loc = source.program.loc
    where = (SourceLocation(source.path, loc.line, loc.col) if loc.line > 0
             else SourceLocation(source.path, 1, 1))
    raise OrccadError("the file declares no mission (write 'mission NAME { ... }')", where)


def compile_mission(source: Source, mission: ast.Mission, *, view: str = COMPOSED,
                    max_states: int = DEFAULT_MAX_STATES,
                    lazy: bool = False) -> Automaton | LazyAutomaton:
    """The minimized automaton of ``mission`` (with ``lazy``: built as it runs, see
    :mod:`orccad_app.reactive.lazy`).

    ``view`` is ``composed`` (the application automaton with the RTAs of its Robot-Tasks
    inlined: what is checked and run) or ``abstract`` (Robot-Tasks seen through their start
    and outcome signals: what ``orccad react`` drives). See :mod:`orccad_app.robottask.application`.
    """
    if view == ABSTRACT:
        program = lower_mission(source.program, mission, AbstractApplicationLowerer)
        if lazy:
            return LazyAutomaton(program, max_states=max_states)
        return compile_program(program, max_states=max_states)
    return compose_mission(source, mission, max_states=max_states, lazy=lazy).automaton


def compose_mission(source: Source, mission: ast.Mission, *,
                    max_states: int = DEFAULT_MAX_STATES, lazy: bool = False,
                    defer_double_emissions: bool = False) -> Composition:
    """The composed automaton of ``mission`` with its ``run`` sites and signal roles (what the
    checker and the mission layer start from); ``lazy`` for a run (states built on demand);
    ``defer_double_emissions`` for a full automaton that runs (``orccad codegen``): see
    :func:`~orccad_app.reactive.compiler.compile_program`."""
    return compose(source.program, mission, max_states=max_states, lazy=lazy,
                   defer_double_emissions=defer_double_emissions)
