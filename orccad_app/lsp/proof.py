"""The proof in the editor: on save (or the command ``orccad.check``), ``orccad check``'s
engine runs on the document in a child process (:mod:`.prove`) with a wall-time budget; each
``property`` line gets its verdict as a diagnostic — *proved* (information), *false* (an
error, with the counterexample's ``.in`` script as related information: the file it is
written to, ready for ``orccad react --composed --inputs`` or ``orccad run --inject-from``)
or *left to runs* (a signal property) — and a change to the document kills the process.
"""

from __future__ import annotations

import asyncio
import hashlib
import json
import logging
import os
import re
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

from lsprotocol import types

from orccad_app.diagnostics import SourceLocation
from orccad_app.lang import ast
from orccad_app.lsp.positions import TextLines, uri_of_path
from orccad_app.lsp.problems import SOURCE, to_range

__all__ = ["Verdict", "ProofRunner", "verdict_diagnostics", "counterexample_folder"]

logger = logging.getLogger(__name__)


@dataclass(frozen=True)
class Verdict:
    """What the proof said of one property (over every mission it applies to)."""

    mission: str | None
    name: str
    state: str  #: ``proved``, ``false`` or ``left to runs``
    message: str = ""
    script_path: str | None = None

    def text(self) -> str:
        return self.state + (f": {self.message}" if self.message else "")


def counterexample_folder() -> Path:
    """Where counterexample scripts are written (a per-user cache folder)."""
    base = Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache")
    return base / "orccad" / "counterexamples"


def _write_script(path: str, mission: str, name: str, script: str) -> str | None:
    folder = counterexample_folder()
    digest = hashlib.sha256(os.path.realpath(path).encode()).hexdigest()[:8]
    target = folder / f"{Path(path).stem}-{digest}-{mission}.{name}.in"
    try:
        folder.mkdir(parents=True, exist_ok=True, mode=0o700)
        target.write_text(script.rstrip("\n") + "\n", encoding="utf-8")
    except OSError as error:
        logger.warning("cannot write %s: %s", target, error)
        return None
    return str(target)


def verdicts_of(path: str, program: ast.Program, answer: dict) -> list[Verdict]:
    """One verdict per property of ``program`` declared in ``path``, from the prover's
    ``answer`` (a property over several missions is false if false in one)."""
    out = []
    for prop in program.properties:
        if prop.loc.file != path:
            continue
        matching = [v for v in answer.get("verdicts", ()) if v["kind"] == "property"
                    and v["name"] == prop.name and prop.mission in (None, v["mission"])]
        left = [m for m, names in answer.get("signal_properties", {}).items()
                if prop.name in names and prop.mission in (None, m)]
        false = next((v for v in matching if not v["holds"]), None)
        if false is not None:
            script = None if false["script"] is None else _write_script(
                path, false["mission"], prop.name, false["script"])
            out.append(Verdict(prop.mission, prop.name, "false",
                               f"{false['message']} (mission {false['mission']})", script))
        elif matching:
            out.append(Verdict(prop.mission, prop.name, "proved"))
        elif left:
            out.append(Verdict(prop.mission, prop.name, "left to runs",
                               "a signal property (STL) is judged on runs and campaigns"))
    return out


def verdict_diagnostics(program: ast.Program, verdicts: list[Verdict], lines: TextLines,
                        path: str) -> list[types.Diagnostic]:
    """The diagnostics of ``verdicts``, each on its ``property`` line."""
    props = {(p.mission, p.name): p for p in program.properties if p.loc.file == path}
    out = []
    for verdict in verdicts:
        prop = props.get((verdict.mission, verdict.name))
        if prop is None:
            continue
        line = lines.line(prop.loc.line - 1)
        end = len(line.rstrip())
        match = re.search(r"\S.*?(?=:)", line[prop.loc.col - 1:])  # `property M.name`
        if match is not None:
            end = prop.loc.col - 1 + match.end()
        where = SourceLocation(path, prop.loc.line, prop.loc.col, prop.loc.line, end + 1)
        label = f"{verdict.mission + '.' if verdict.mission else ''}{verdict.name}"
        if verdict.state == "false":
            related = None
            if verdict.script_path is not None:
                related = [types.DiagnosticRelatedInformation(
                    types.Location(uri_of_path(verdict.script_path),
                                   types.Range(types.Position(0, 0), types.Position(0, 0))),
                    "counterexample: an input script for orccad react --composed --inputs")]
            out.append(types.Diagnostic(
                to_range(where, lines), f"property {label} is false: {verdict.message}",
                severity=types.DiagnosticSeverity.Error, source=SOURCE, code="proof",
                related_information=related))
        else:
            text = "proved" if verdict.state == "proved" else f"left to runs: {verdict.message}"
            out.append(types.Diagnostic(
                to_range(where, lines), f"property {label}: {text}",
                severity=types.DiagnosticSeverity.Information, source=SOURCE, code="proof"))
    return out


class ProofRunner:
    """At most one proof per document, each in a child process; cancel kills it."""

    def __init__(self, budget_s: float, max_states: int = 20_000) -> None:
        self.budget_s = budget_s
        self.max_states = max_states
        self.tasks: dict[str, asyncio.Task] = {}
        self.processes: dict[str, asyncio.subprocess.Process] = {}

    def running(self, uri: str) -> bool:
        task = self.tasks.get(uri)
        return task is not None and not task.done()

    def start(self, uri: str, path: str, text: str, buffers: dict[str, str],
              done: Callable[[dict], None], started: Callable[[int], None]) -> None:
        """Prove ``uri`` (its text ``text``) in the background: ``started(pid)`` once its
        process runs, ``done(answer)`` with the prover's answer (or ``{"error": …}`` for a
        budget spent or a crash); neither after a cancel."""
        self.cancel(uri)
        self.tasks[uri] = asyncio.ensure_future(self._run(uri, path, text, buffers, done,
                                                          started))

    async def _run(self, uri: str, path: str, text: str, buffers: dict[str, str],
                   done: Callable[[dict], None], started: Callable[[int], None]) -> None:
        request = json.dumps({"path": path, "text": text, "buffers": buffers,
                              "max_states": self.max_states}).encode()
        process = await asyncio.create_subprocess_exec(
            sys.executable, "-m", "orccad_app.lsp.prove", stdin=asyncio.subprocess.PIPE,
            stdout=asyncio.subprocess.PIPE, stderr=asyncio.subprocess.PIPE)
        self.processes[uri] = process
        started(process.pid)
        try:
            out, err = await asyncio.wait_for(process.communicate(request), self.budget_s)
        except TimeoutError:
            await self._kill(process)
            done({"error": {"message": f"the proof ran past its budget of {self.budget_s:g} s "
                                       "(orccad lsp --proof-budget-s): run orccad check",
                            "file": None, "line": 0, "col": 0}})
            return
        except asyncio.CancelledError:
            await self._kill(process)
            raise
        finally:
            self.processes.pop(uri, None)
        try:
            answer = json.loads(out.decode() or "null")
        except ValueError:
            answer = None
        if not isinstance(answer, dict):
            tail = err.decode(errors="replace").strip().splitlines()[-1:] or ["no answer"]
            answer = {"error": {"message": f"the proof failed: {tail[0]}", "file": None,
                                "line": 0, "col": 0}}
        done(answer)

    @staticmethod
    async def _kill(process: asyncio.subprocess.Process) -> None:
        if process.returncode is None:
            try:
                process.kill()
            except ProcessLookupError:
                pass
            await process.wait()

    def cancel(self, uri: str) -> bool:
        """Stop the proof of ``uri`` (its process killed); whether one was running."""
        task = self.tasks.pop(uri, None)
        if task is None or task.done():
            return False
        task.cancel()
        return True

    def cancel_all(self) -> None:
        for uri in list(self.tasks):
            self.cancel(uri)
        for process in list(self.processes.values()):
            if process.returncode is None:
                try:
                    process.kill()
                except ProcessLookupError:
                    pass
