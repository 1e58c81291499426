"""The proof in the editor: verdicts on each property line after a save, a false one with
its counterexample script, and a change that cancels a running proof (its process killed)."""

from __future__ import annotations

import asyncio
import os
import re
import shutil
import tempfile
from pathlib import Path

import pytest
import pytest_lsp
from lsprotocol import types
from pytest_lsp import LanguageClient

from tests.lsp.conftest import (MISSIONS, close_document, config, diagnostics_of, initialize,
                                open_document, uri)

pytestmark = pytest.mark.asyncio(loop_scope="module")

#: The server's cache folder (counterexample scripts), removed after the module.
CACHE = tempfile.mkdtemp(prefix="orccad-lsp-proof-")


@pytest_lsp.fixture(scope="module",
                    config=config(server_env={**os.environ, "XDG_CACHE_HOME": CACHE}))
async def client(lsp_client: LanguageClient):
    await initialize(lsp_client)
    yield
    await lsp_client.shutdown_session()
    shutil.rmtree(CACHE, ignore_errors=True)


def _save(client: LanguageClient, path: Path) -> int:
    since = len(client.published)
    client.text_document_did_save(types.DidSaveTextDocumentParams(
        types.TextDocumentIdentifier(uri(path))))
    return since


async def _verdicts(client, path: Path, since: int) -> dict[int, types.Diagnostic]:
    """The proof's diagnostics of ``path`` first published after ``since``, by line."""
    async def proved():
        while True:
            for params in client.published[since:]:
                if params.uri == uri(path) and any(d.code == "proof" for d in params.diagnostics):
                    return params.diagnostics
            await asyncio.sleep(0.05)
    diagnostics = await asyncio.wait_for(proved(), 240)
    return {d.range.start.line: d for d in diagnostics if d.code == "proof"}


def _property_lines(path: Path) -> dict[str, int]:
    return {m.group(1): number for number, line in enumerate(path.read_text().split("\n"))
            if (m := re.match(r"property\s+\w+\.(\w+)", line))}


async def test_a_false_property_gets_an_error_with_its_counterexample_script(client):
    path = MISSIONS / "false_property.orc"
    assert await open_document(client, path) == []
    verdicts = await _verdicts(client, path, _save(client, path))
    lines = _property_lines(path)
    assert set(verdicts) == set(lines.values())
    for name, line in lines.items():
        verdict = verdicts[line]
        if verdict.severity == types.DiagnosticSeverity.Error:
            assert f"{name} is false" in verdict.message
            script = Path(verdict.related_information[0].location.uri.removeprefix("file://"))
            text = script.read_text()
            assert text.startswith(f"# counterexample to property PickPlace.{name}")
            assert "orccad react" in text and "--composed" in text
        else:
            assert verdict.message.endswith(": proved")
    false = [line for line, d in verdicts.items() if d.severity == types.DiagnosticSeverity.Error]
    assert len(false) == 2
    hover = await client.text_document_hover_async(types.HoverParams(
        types.TextDocumentIdentifier(uri(path)),
        types.Position(false[0], path.read_text().split("\n")[false[0]].index(".") + 1)))
    assert "last verdict: **false" in hover.contents.value
    close_document(client, path)


async def test_every_property_of_arm_recovery_is_proved(client):
    path = MISSIONS / "arm_recovery.orc"
    await open_document(client, path)
    verdicts = await _verdicts(client, path, _save(client, path))
    lines = _property_lines(path)
    assert len(lines) == 7
    assert {line: d.message.rsplit(": ", 1)[-1] for line, d in verdicts.items()} == {
        line: "proved" for line in lines.values()}
    assert all(d.severity == types.DiagnosticSeverity.Information for d in verdicts.values())
    close_document(client, path)


async def _log(client: LanguageClient, pattern: str, since: int, timeout_s: float = 120):
    async def found():
        while True:
            for message in client.log_messages[since:]:
                match = re.search(pattern, message.message)
                if match:
                    return match
            await asyncio.sleep(0.02)
    return await asyncio.wait_for(found(), timeout_s)


async def test_a_change_cancels_a_running_proof_and_kills_its_process(client, tmp_path):
    path = tmp_path / "recovery.orc"
    shutil.copytree(MISSIONS / "lib", tmp_path / "lib")
    text = (MISSIONS / "arm_recovery.orc").read_text()
    path.write_text(text)
    await open_document(client, path)
    logs = len(client.log_messages)
    since = _save(client, path)
    started = await _log(client, r"proof of .*recovery\.orc started \(process (\d+)\)", logs)
    pid = int(started.group(1))
    client.text_document_did_change(types.DidChangeTextDocumentParams(
        text_document=types.VersionedTextDocumentIdentifier(uri=uri(path), version=2),
        content_changes=[types.TextDocumentContentChangeWholeDocument(text=text + "\n")]))
    await _log(client, r"proof of .*recovery\.orc cancelled", logs)
    await diagnostics_of(client, uri(path), 2, since)
    for _ in range(100):  # the process is killed and reaped
        try:
            os.kill(pid, 0)
        except ProcessLookupError:
            break
        await asyncio.sleep(0.05)
    else:
        raise AssertionError(f"proof process {pid} still alive")
    await asyncio.sleep(0.5)
    proof = [p for p in client.published[since:] if p.uri == uri(path)
             and any(d.code == "proof" for d in p.diagnostics)]
    assert proof == []
    close_document(client, path)


async def test_a_compile_error_comes_with_the_proof_at_its_place(client, tmp_path):
    """Errors only compiling finds (here a non-causal program) are the proof's: located."""
    path = tmp_path / "causal.orc"
    text = "mission M {\n    output S;\n    if S { nothing; } else { emit S; }\n}\n"
    assert await open_document(client, path, text) == []
    verdicts = await _verdicts(client, path, _save(client, path))
    assert list(verdicts) == [2], verdicts
    assert verdicts[2].severity == types.DiagnosticSeverity.Error
    close_document(client, path)


async def test_signal_properties_are_left_to_runs(client):
    from orccad_app.lang import ast
    from orccad_app.lang.parser import parse

    path = MISSIONS / "arm_computed_torque.orc"
    program = parse(path.read_text(), str(path))
    signal = {p.loc.line - 1 for p in program.properties if ast.is_signal_formula(p.formula)}
    assert len(signal) == 3
    await open_document(client, path)
    verdicts = await _verdicts(client, path, _save(client, path))
    assert set(verdicts) == {p.loc.line - 1 for p in program.properties}
    for line, verdict in verdicts.items():
        expected = "left to runs" if line in signal else "proved"
        assert expected in verdict.message, verdict.message
        assert verdict.severity == types.DiagnosticSeverity.Information
    close_document(client, path)


SMALL = """input Go;
output Done;
mission M { await Go; emit Done; }
property M.done_after_go: always (Done -> once Go);
"""


@pytest.mark.parametrize("shape", ["uri", "identifier", "list"])
async def test_the_check_command_takes_the_arguments_clients_send(client, tmp_path, shape):
    """``[uri]`` (the shipped VS Code extension's), ``[{"uri": uri}]`` and ``[[uri]]``, for
    a file in a folder whose name the URI escapes (a space)."""
    folder = tmp_path / "my missions"
    folder.mkdir()
    path = folder / "small.orc"
    path.write_text(SMALL)
    assert await open_document(client, path) == []
    target = uri(path)
    assert "%20" in target
    argument = {"uri": target, "identifier": {"uri": target}, "list": [target]}[shape]
    since = len(client.published)
    answer = await client.workspace_execute_command_async(types.ExecuteCommandParams(
        command="orccad.check", arguments=[argument]))
    assert answer == f"proof of {target} started"
    verdicts = await _verdicts(client, path, since)
    assert [d.message for d in verdicts.values()] == ["property M.done_after_go: proved"]
    close_document(client, path)


@pytest.mark.parametrize("arguments", [[], [5], [["a", "b"]], [{"path": "x"}], None])
async def test_the_check_command_refuses_other_arguments_saying_what_it_takes(client,
                                                                               arguments):
    with pytest.raises(Exception, match=r"expected the URI of an open document"):
        await client.workspace_execute_command_async(types.ExecuteCommandParams(
            command="orccad.check", arguments=arguments))


async def test_the_check_command_refuses_a_document_that_is_not_open(client, tmp_path):
    with pytest.raises(Exception, match=r"is not an open document"):
        await client.workspace_execute_command_async(types.ExecuteCommandParams(
            command="orccad.check", arguments=[uri(tmp_path / "closed.orc")]))
