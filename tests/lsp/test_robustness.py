"""The server's robustness: a plugin that raises, a document that does not parse (outline
and folding still given)."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
import pytest_lsp
from lsprotocol import types
from pytest_lsp import LanguageClient

from tests.lsp.conftest import (MISSIONS, ROOT, close_document, config, initialize,
                                open_document, uri)

pytestmark = pytest.mark.asyncio(loop_scope="module")

PLUGINS = Path(__file__).parent / "data" / "raising_plugins"
ENV = {**os.environ, "ORCCAD_DISABLE_PLUGINS": "",
       "PYTHONPATH": os.pathsep.join([str(PLUGINS), str(ROOT), os.environ.get("PYTHONPATH", "")])}


@pytest_lsp.fixture(scope="module",
                    config=config(server_env=ENV))
async def client(lsp_client: LanguageClient):
    await initialize(lsp_client)
    yield
    await lsp_client.shutdown_session()


async def test_a_plugin_that_raises_is_one_diagnostic_and_the_rest_works(client):
    path = MISSIONS / "arm_pid.orc"
    diagnostics = await open_document(client, path)
    about_plugin = [d for d in diagnostics if "lsp_raising" in d.message]
    assert len(about_plugin) == 1
    assert "broken on purpose" in about_plugin[0].message
    assert about_plugin[0].severity == types.DiagnosticSeverity.Warning
    assert [d for d in diagnostics if d.severity == types.DiagnosticSeverity.Error] == []
    close_document(client, path)


BROKEN = """robot arm : arm3dof;
input Go;
output Done;

mission First {
    await Go;
    emit Done;
}

mission Broken {
    await Go
    emit (Done;
    par { nothing; } || {
        nothing;
    }
}

robottask Later() on arm {
    duration 1 s;
}

property First.done_after_go: always (Done -> once Go);
"""


async def test_a_syntax_error_in_the_middle_still_gets_an_outline_and_folding(client, tmp_path):
    path = tmp_path / "broken.orc"
    diagnostics = await open_document(client, path, BROKEN)
    assert len(diagnostics) == 1 and diagnostics[0].range.start.line == 10  # the missing ;
    symbols = await client.text_document_document_symbol_async(
        types.DocumentSymbolParams(types.TextDocumentIdentifier(uri(path))))
    names = [(s.name, s.kind) for s in symbols]
    assert names == [("arm", types.SymbolKind.Object), ("Go", types.SymbolKind.Event),
                     ("Done", types.SymbolKind.Event), ("First", types.SymbolKind.Function),
                     ("Broken", types.SymbolKind.Function), ("Later", types.SymbolKind.Class),
                     ("First.done_after_go", types.SymbolKind.Boolean)]
    broken = symbols[4]
    assert (broken.range.start.line, broken.range.end.line) == (9, 15)
    folds = await client.text_document_folding_range_async(
        types.FoldingRangeParams(types.TextDocumentIdentifier(uri(path))))
    assert {(f.start_line, f.end_line) for f in folds} >= {(4, 6), (9, 14), (12, 13), (17, 18)}
    close_document(client, path)


async def test_the_outline_of_a_mission_that_parses(client):
    path = MISSIONS / "arm_recovery.orc"
    await open_document(client, path)
    symbols = await client.text_document_document_symbol_async(
        types.DocumentSymbolParams(types.TextDocumentIdentifier(uri(path))))
    by_name = {s.name: s for s in symbols}
    task = by_name["TrackPID"]
    assert task.kind == types.SymbolKind.Class
    assert [c.name for c in task.children] == ["q0", "kp", "traj", "ctrl", "jl", "JointLimit",
                                               "TrackingLost", "Saturated"]
    assert task.selection_range.start.line == 16 and task.selection_range.start.character == 10
    mission = by_name["ArmRecovery"]
    runs = [c.name for c in mission.children if c.detail in ("run", "run mission")]
    assert runs == ["Homing", "TrackPID", "Homing", "Parking"]
    assert "ArmRecovery.finished_once" in by_name
    close_document(client, path)


async def test_bad_requests_get_answers_and_the_server_goes_on(client, tmp_path):
    path = tmp_path / "small.orc"
    await open_document(client, path, "mission M { output O; emit O; }\n")
    target = types.TextDocumentIdentifier(uri(path))
    far = types.Position(1000, 1000)
    assert await client.text_document_hover_async(types.HoverParams(target, far)) is None
    assert await client.text_document_definition_async(
        types.DefinitionParams(target, far)) is None
    items = await client.text_document_completion_async(types.CompletionParams(target, far))
    assert items is not None
    # a change to a document the server was never told of, then a normal request
    client.text_document_did_change(types.DidChangeTextDocumentParams(
        text_document=types.VersionedTextDocumentIdentifier(uri=uri(tmp_path / "nope.orc"),
                                                            version=2),
        content_changes=[types.TextDocumentContentChangeWholeDocument(text="x")]))
    symbols = await client.text_document_document_symbol_async(
        types.DocumentSymbolParams(target))
    assert [s.name for s in symbols] == ["M"]
    close_document(client, path)


async def test_an_import_cycle_is_located_at_the_import_that_closes_it(client, tmp_path):
    a, b = tmp_path / "a.orc", tmp_path / "b.orc"
    b.write_text('from "a.orc" import A;\nmission B [output O] { run mission A; }\n')
    a.write_text('from "b.orc" import B;\nmission A [output O] { emit O; }\n')
    diagnostics = await open_document(client, a)
    assert len(diagnostics) == 1 and "import cycle" in diagnostics[0].message
    assert diagnostics[0].range.start.line == 0
    close_document(client, a)
