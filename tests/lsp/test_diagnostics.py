"""Diagnostics end to end: ``orccad lsp`` as a subprocess, one session for the module."""

from __future__ import annotations

from pathlib import Path

import pytest
import pytest_lsp
from lsprotocol import types
from pytest_lsp import LanguageClient

from tests.lsp.conftest import (MISSIONS, change_document, close_document, config,
                                diagnostics_of, initialize, open_document, uri)

pytestmark = pytest.mark.asyncio(loop_scope="module")


@pytest_lsp.fixture(scope="module", config=config())
async def client(lsp_client: LanguageClient):
    await initialize(lsp_client)
    yield
    await lsp_client.shutdown_session()


ARM = """robot arm : arm3dof;
robottask Hold() on arm {
    duration 1 s;
    task_function joint_tracking(trajectory = constant(value = [0.0, 0.0, 0.0]));
    law pid(kp = 400.0, kv = 40.0);
}
"""

#: Each kind of error of docs/limits.md (and the checker's), with the line it is reported
#: at (1-based) and a part of its message.
ERRORS = {
    "syntax": ("mission M {\n    emit ;\n}\n", 2, "expected"),
    "reserved keyword": ("mission M {\n    output loop;\n    emit loop;\n}\n", 2, "reserved"),
    "undeclared signal": ("mission M {\n    output O;\n    await C;\n}\n", 3, "'C'"),
    "integer literal": ("mission M {\n    output N : int;\n    emit N(9223372036854775808);\n}\n",
                        3, "9223372036854775807"),
    "real literal": ("mission M {\n    output R : float;\n    emit R(1e400);\n}\n", 3, "finite"),
    "duration not whole ns": ("mission M {\n    await 1.5 ns;\n}\n", 2, "nanosecond"),
    "duration over a year": ("mission M {\n    await 1e400 s;\n}\n", 2, ""),
    "zero period": (ARM.replace("law pid(kp = 400.0, kv = 40.0);",
                                "law pid(kp = 400.0, kv = 40.0);\n    module ctrl : control_law "
                                "period 0 ms;") + "mission M { run Hold(); }\n", 6, "period"),
    "named argument twice": (ARM.replace("kv = 40.0", "kv = 40.0, kv = 1.0")
                             + "mission M { run Hold(); }\n", 5, "kv"),
    "zero Robot-Task duration": (ARM.replace("duration 1 s", "duration 0 s")
                                 + "mission M { run Hold(); }\n", 3, "duration"),
    "nesting": ("mission M {\n" + "par {\n" * 101 + "nothing;" + "}\n" * 101 + "}\n", 102,
                "100"),
    "unknown law": (ARM.replace("law pid", "law pdi") + "mission M { run Hold(); }\n", 5,
                    "pdi"),
    "missing import": ('from "lib/nothing.orc" import X;\nmission M { run mission X; }\n', 1,
                       "no such file"),
}


@pytest.mark.parametrize("kind", sorted(ERRORS))
async def test_each_kind_of_error_is_one_located_diagnostic(client: LanguageClient,
                                                            tmp_path: Path, kind: str):
    text, line, part = ERRORS[kind]
    path = tmp_path / "m.orc"
    diagnostics = await open_document(client, path, text)
    errors = [d for d in diagnostics if d.severity == types.DiagnosticSeverity.Error]
    assert errors, f"{kind}: no error for {text!r}"
    first = errors[0]
    assert first.range.start.line == line - 1, (kind, first)
    assert part in first.message, (kind, first.message)
    assert first.source == "orccad"
    close_document(client, path)


async def test_every_shipped_mission_opens_without_errors(client: LanguageClient):
    for path in sorted(MISSIONS.glob("*.orc")):
        diagnostics = await open_document(client, path)
        errors = [d.message for d in diagnostics if d.severity == types.DiagnosticSeverity.Error]
        assert errors == [], path.name
        close_document(client, path)


async def test_all_errors_of_a_file_are_reported_not_only_the_first(client, tmp_path):
    text = "mission M {\n    output O;\n    await A;\n    emit B;\n}\n"
    diagnostics = await open_document(client, tmp_path / "two.orc", text)
    assert sorted(d.range.start.line for d in diagnostics) == [2, 3]
    close_document(client, tmp_path / "two.orc")


async def test_a_change_is_analysed_from_the_buffer_not_the_disk(client, tmp_path):
    path = tmp_path / "edit.orc"
    path.write_text("mission M { output O; emit O; }\n")
    assert await open_document(client, path) == []
    diagnostics = await change_document(client, path, "mission M { output O; emit P; }\n", 2)
    assert [d.message for d in diagnostics] == ["undeclared signal 'P'"]
    assert await change_document(client, path, "mission M { output O; emit O; }\n", 3) == []
    close_document(client, path)


async def test_an_error_in_an_imported_file_is_shown_at_the_import_and_in_that_file(
        client, tmp_path):
    (tmp_path / "lib").mkdir()
    library = tmp_path / "lib" / "h.orc"
    library.write_text("mission Hello [output Hi] {\n    emit Hello2;\n}\n")
    main = tmp_path / "main.orc"
    text = 'from "lib/h.orc" import Hello;\nmission M { output Hi; run mission Hello; }\n'
    since = len(client.published)
    diagnostics = await open_document(client, main, text)
    assert len(diagnostics) == 1
    at_import = diagnostics[0]
    assert at_import.range.start.line == 0 and "Hello2" in at_import.message
    related = at_import.related_information
    assert related and related[0].location.uri == uri(library)
    assert related[0].location.range.start.line == 1
    in_library = await diagnostics_of(client, uri(library), None, since)
    assert [d.range.start.line for d in in_library] == [1]
    close_document(client, main)


async def test_an_import_reads_the_unsaved_buffer_of_an_open_document(client, tmp_path):
    library = tmp_path / "lib.orc"
    library.write_text("mission Hello [output Hi] { emit Hi; }\n")
    main = tmp_path / "main2.orc"
    text = 'from "lib.orc" import Hello;\nmission M { output Hi; run mission Hello; }\n'
    assert await open_document(client, library) == []
    assert await open_document(client, main, text) == []
    # the library is renamed in the editor, not saved: the importer sees the buffer
    since = len(client.published)
    await change_document(client, library, "mission Hola [output Hi] { emit Hi; }\n", 2)
    diagnostics = await diagnostics_of(client, uri(main), 1, since)
    assert len(diagnostics) == 1 and "no mission 'Hello'" in diagnostics[0].message
    close_document(client, main)
    close_document(client, library)


async def test_a_huge_or_binary_buffer_is_refused_with_one_message(client, tmp_path):
    huge = "// " + "x" * 600_000 + "\nmission M { }\n"
    diagnostics = await open_document(client, tmp_path / "huge.orc", huge)
    assert len(diagnostics) == 1 and "512000 bytes" in diagnostics[0].message
    target = types.TextDocumentIdentifier(uri(tmp_path / "huge.orc"))
    end = types.Position(1, 12)
    completion = await client.text_document_completion_async(
        types.CompletionParams(target, end))
    assert list(completion.items) == []
    assert await client.text_document_hover_async(types.HoverParams(target, end)) is None
    assert await client.text_document_document_symbol_async(
        types.DocumentSymbolParams(target)) in ([], ())
    diagnostics = await open_document(client, tmp_path / "bin.orc", "mission\0\0\x01")
    assert len(diagnostics) == 1 and "binary" in diagnostics[0].message
    # the server still answers
    assert await open_document(client, tmp_path / "ok.orc", "mission M { nothing; }") == []
