"""Hover, go to definition and references on every shipped mission, through the server."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
import pytest_lsp
from lsprotocol import types
from pytest_lsp import LanguageClient

from orccad_app.lang import ast
from orccad_app.lang.parser import parse
from orccad_app.lang.walk import nodes
from tests.lsp.conftest import MISSIONS, config, close_document, initialize, open_document, uri

pytestmark = pytest.mark.asyncio(loop_scope="module")

SHIPPED = sorted(MISSIONS.glob("*.orc")) + sorted((MISSIONS / "lib").glob("*.orc"))


@pytest_lsp.fixture(scope="module", config=config())
async def client(lsp_client: LanguageClient):
    await initialize(lsp_client)
    yield
    await lsp_client.shutdown_session()


def _name_position(text: str, loc, name: str) -> types.Position:
    """Where ``name`` is written from ``loc`` on (0-based)."""
    lines = text.split("\n")
    for number in range(loc.line - 1, len(lines)):
        start = loc.col - 1 if number == loc.line - 1 else 0
        match = re.compile(rf"\b{re.escape(name)}\b").search(lines[number], start)
        if match:
            return types.Position(number, match.start())
    raise AssertionError(f"{name} not found after {loc}")


async def _hover(client, path, position) -> str:
    result = await client.text_document_hover_async(types.HoverParams(
        types.TextDocumentIdentifier(uri(path)), position))
    assert result is not None, position
    return result.contents.value


async def _definition(client, path, position) -> types.Location:
    result = await client.text_document_definition_async(types.DefinitionParams(
        types.TextDocumentIdentifier(uri(path)), position))
    assert isinstance(result, types.Location), (path.name, position, result)
    return result


@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: p.name)
async def test_hover_and_definition_of_every_run_signal_and_task(client, path: Path):
    text = path.read_text()
    program = parse(text, str(path))
    await open_document(client, path)
    tasks = {t.name: t for t in program.robottasks}
    checked = 0
    for mission in program.missions:
        for node in nodes(mission):
            if isinstance(node, ast.Run) and node.task in tasks:
                at = _name_position(text, node.loc, node.task)
                hover = await _hover(client, path, at)
                assert f"robottask {node.task}(" in hover
                assert "| Module-Task | kind | period | WCET | processor |" in hover
                target = await _definition(client, path, at)
                declared = _name_position(text, tasks[node.task].loc, node.task)
                assert (target.uri, target.range.start) == (uri(path), declared)
                checked += 1
            elif isinstance(node, ast.RunMission):
                at = _name_position(text, node.loc, node.mission)
                target = await _definition(client, path, at)
                assert target.uri.endswith(".orc")
                other = Path(target.uri.removeprefix("file://")).read_text().split("\n")
                assert re.search(rf"mission\s+{node.mission}\b", other[target.range.start.line])
                checked += 1
            elif isinstance(node, ast.Emit):
                at = _name_position(text, node.loc, node.signal)
                hover = await _hover(client, path, at)
                assert re.search(rf"(output|local signal) {node.signal}\b", hover), hover
                target = await _definition(client, path, at)
                line = text.split("\n")[target.range.start.line]
                assert re.search(rf"\b{node.signal}\b", line)
                checked += 1
    for task in program.robottasks:
        for exception in task.exceptions:
            at = _name_position(text, exception.loc, exception.name)
            hover = await _hover(client, path, at)
            assert f"exception {exception.name} : {exception.type.value}" in hover
            assert f"type {exception.type.number}" in hover
            checked += 1
        if task.law is not None:
            lines = text.split("\n")
            line = next(i for i in range(task.loc.line - 1, len(lines))
                        if re.match(r"\s*law\s", lines[i]))
            at = types.Position(line, lines[line].index(task.law.func,
                                                        lines[line].index("law") + 3))
            hover = await _hover(client, path, at)
            assert f"**control law** `{task.law.func}`" in hover
            assert "| parameter | type | default | range | meaning |" in hover
            checked += 1
    assert checked or not program.missions, f"nothing to check in {path.name}"
    close_document(client, path)


async def test_hover_on_a_law_gives_units_and_ranges(client):
    path = MISSIONS / "arm_pid.orc"
    text = path.read_text()
    await open_document(client, path)
    line = next(i for i, t in enumerate(text.split("\n")) if t.strip().startswith("law pid"))
    hover = await _hover(client, path, types.Position(line, text.split("\n")[line].index("pid")))
    assert "| `kp` | float\\|vector | `400` | (0, ∞) | proportional gain [N·m/rad] |" in hover
    close_document(client, path)


async def test_hover_on_a_signal_says_direction_type_and_role(client):
    path = MISSIONS / "arm_recovery.orc"
    text = path.read_text()
    await open_document(client, path)
    lines = text.split("\n")
    line = next(i for i, t in enumerate(lines) if "if ?Gripper" in t)
    hover = await _hover(client, path, types.Position(line, lines[line].index("Gripper")))
    assert "input Gripper : float" in hover and "from the environment" in hover
    assert "tested or read at" in hover
    close_document(client, path)


async def test_references_of_a_signal_and_a_robottask(client):
    path = MISSIONS / "arm_recovery.orc"
    text = path.read_text()
    await open_document(client, path)
    lines = text.split("\n")
    decl_line = next(i for i, t in enumerate(lines) if t.startswith("input Stop"))
    refs = await client.text_document_references_async(types.ReferenceParams(
        text_document=types.TextDocumentIdentifier(uri(path)),
        position=types.Position(decl_line, 6),
        context=types.ReferenceContext(include_declaration=True)))
    used = [i for i, t in enumerate(lines) if re.search(r"\bStop\b", t.split("//")[0])]
    assert sorted({r.range.start.line for r in refs}) == used
    task_line = next(i for i, t in enumerate(lines) if t.startswith("robottask TrackPID"))
    refs = await client.text_document_references_async(types.ReferenceParams(
        text_document=types.TextDocumentIdentifier(uri(path)),
        position=types.Position(task_line, 12),
        context=types.ReferenceContext(include_declaration=False)))
    used = [i for i, t in enumerate(lines)
            if re.search(r"\bTrackPID\b", t.split("//")[0]) and i != task_line]
    assert sorted(r.range.start.line for r in refs) == used
    close_document(client, path)


async def test_definition_of_an_imported_mission_opens_its_file(client):
    path = MISSIONS / "arm_recovery.orc"
    text = path.read_text()
    await open_document(client, path)
    lines = text.split("\n")
    line = next(i for i, t in enumerate(lines) if "import Homing" in t)
    target = await _definition(client, path, types.Position(line, lines[line].index("Homing")))
    assert target.uri == uri(MISSIONS / "lib" / "homing.orc")
    library = (MISSIONS / "lib" / "homing.orc").read_text().split("\n")
    assert "mission Homing" in library[target.range.start.line]
    close_document(client, path)


async def test_definition_of_robots_variables_modules_exceptions_and_traps(client):
    path = MISSIONS / "arm_recovery.orc"
    text = path.read_text()
    lines = text.split("\n")
    await open_document(client, path)

    def at(line_text: str, name: str, nth: int = 0) -> types.Position:
        line = [i for i, t in enumerate(lines) if line_text in t][nth]
        return types.Position(line, lines[line].index(name, lines[line].index(line_text)))

    def line_of(prefix: str) -> int:
        return next(i for i, t in enumerate(lines) if t.strip().startswith(prefix))

    cases = [(at("on arm {", "arm"), line_of("robot arm")),
             (at("emit Retry(tries)", "tries"), line_of("var tries")),
             (at("connect ctrl.tau", "ctrl"), line_of("module ctrl")),
             (at("catch TrackingLost", "TrackingLost"), line_of("exception TrackingLost")),
             (at("exit Success", "Success"), line_of("trap Success")),
             (at("await immediate Tracked", "Tracked"), line_of("signal Tracked"))]
    for position, declared in cases:
        target = await _definition(client, path, position)
        assert (target.uri, target.range.start.line) == (uri(path), declared), position
    close_document(client, path)
