"""Completion through the server: keywords from the grammar in context, registry names and
Robot-Tasks as snippets with their parameters, protocols, signals in scope."""

from __future__ import annotations

from pathlib import Path

import pytest
import pytest_lsp
from lsprotocol import types
from pytest_lsp import LanguageClient

from tests.lsp.conftest import ROOT, close_document, config, open_document, uri

pytestmark = pytest.mark.asyncio(loop_scope="module")


@pytest_lsp.fixture(scope="module", config=config())
async def client(lsp_client: LanguageClient):
    capabilities = types.ClientCapabilities(text_document=types.TextDocumentClientCapabilities(
        completion=types.CompletionClientCapabilities(
            completion_item=types.ClientCompletionItemOptions(snippet_support=True))))
    await lsp_client.initialize_session(types.InitializeParams(
        capabilities=capabilities, root_uri=uri(ROOT)))
    yield
    await lsp_client.shutdown_session()


DOCUMENT = """robot arm : arm3dof;
input Go;
output Done, Level : float;

robottask Move(q: vector = [0.0, 0.5, 0.0], kp: float = 400.0) on arm {
    duration 1 s;
    task_function joint_tracking(trajectory = constant(value = q));
    law pid(kp = kp, kv = 40.0);
    module traj : trajectory period 1 ms wcet 0.1 ms on cpu0 priority 2;
    module ctrl : control_law period 1 ms wcet 0.3 ms on cpu0 priority 1;
    connect traj.qd -> ctrl.qd;
    connect traj.qd_dot -> ctrl.qd_dot;
    connect arm.q -> ctrl.q;
    connect arm.qdot -> ctrl.qdot;
    connect ctrl.tau -> arm.tau;
    exception Lost from tracking_error(max = 0.2) : abort;
}

mission M {
    signal Inner {
        await Go;
        emit Done;
    }
    try { run Move(); } catch Lost { emit Done; }
}
"""


_VERSION = [1]


async def _complete(client: LanguageClient, path: Path, text: str, marker: str,
                    insert: str = "") -> dict[str, types.CompletionItem]:
    """Completion at the end of ``marker`` in ``text`` (with ``insert`` typed there)."""
    at = text.index(marker) + len(marker)
    edited = text[:at] + insert + text[at:]
    _VERSION[0] += 1
    version = _VERSION
    client.text_document_did_change(types.DidChangeTextDocumentParams(
        text_document=types.VersionedTextDocumentIdentifier(uri=uri(path), version=version[0]),
        content_changes=[types.TextDocumentContentChangeWholeDocument(text=edited)]))
    before = edited[:at + len(insert)]
    line = before.count("\n")
    character = len(before) - (before.rfind("\n") + 1)
    result = await client.text_document_completion_async(types.CompletionParams(
        types.TextDocumentIdentifier(uri(path)), types.Position(line, character)))
    items = result.items if isinstance(result, types.CompletionList) else result
    return {item.label: item for item in items}


@pytest.fixture(scope="module")
def document(tmp_path_factory) -> Path:
    return tmp_path_factory.mktemp("completion") / "m.orc"


async def test_a_law_comes_with_its_parameters_as_a_snippet(client, document):
    assert await open_document(client, document, DOCUMENT) == []
    items = await _complete(client, document, DOCUMENT, "    law ")
    assert {"pid", "generic", "computed_torque"} <= set(items)
    pid = items["pid"]
    assert pid.insert_text_format == types.InsertTextFormat.Snippet
    assert pid.insert_text == "pid(kp = ${1:400.0}, kv = ${2:40.0}, ki = ${3:0.0}, " \
                              "anti_windup = ${4:true})"
    assert "emit" not in items  # only what the grammar takes there


async def test_trajectories_observers_module_kinds_and_robot_types(client, document):
    items = await _complete(client, document, DOCUMENT, "joint_tracking(trajectory = ")
    assert {"cosine", "min_jerk", "constant"} <= set(items)
    items = await _complete(client, document, DOCUMENT, "    exception Lost from ")
    assert {"traj", "ctrl", "tracking_error", "joint_limits"} <= set(items)
    assert "pid" not in items
    items = await _complete(client, document, DOCUMENT, "    module ctrl : ")
    assert {"control_law", "trajectory", "joint_limits"} <= set(items)
    items = await _complete(client, document, DOCUMENT, "robot arm : ")
    assert {"arm3dof", "auv"} <= set(items)


async def test_protocols_after_a_connection(client, document):
    items = await _complete(client, document, DOCUMENT, "connect traj.qd -> ctrl.qd", " : ")
    assert set(items) == {"asyn/asyn", "syn/syn", "asyn/syn", "syn/asyn", "asyn/synF",
                          "synF/asyn", "asyn/synD", "asyn/synDF"}


async def test_statement_keywords_and_signals_in_scope(client, document):
    items = await _complete(client, document, DOCUMENT, "        emit Done;\n")
    assert {"emit", "await", "run", "par", "abort", "trap", "var"} <= set(items)
    assert {"Go", "Done", "Level", "Inner"} <= set(items)
    assert "robottask" not in items and "law" not in items
    items = await _complete(client, document, DOCUMENT, "        emit ")
    assert {"Done", "Level", "Inner"} <= set(items)


async def test_a_run_offers_the_robottasks_with_their_parameters(client, document):
    items = await _complete(client, document, DOCUMENT, "    try { run ")
    assert items["Move"].insert_text == "Move(q = ${1:[0.0, 0.5, 0.0]}, kp = ${2:400.0})"
    assert "mission" in items  # run mission …
    items = await _complete(client, document, DOCUMENT, "catch ")
    assert {"Lost", "Timeout"} <= set(items)


async def test_top_level_keywords(client, document):
    items = await _complete(client, document, DOCUMENT, "output Done, Level : float;\n")
    assert {"mission", "robottask", "robot", "input", "output", "property", "from"} <= set(items)
    assert "emit" not in items


async def test_completion_in_a_document_with_a_syntax_error_before_the_cursor(client,
                                                                              document):
    broken = DOCUMENT.replace("await Go;", "await Go")
    items = await _complete(client, document, broken, "        emit Done;\n")
    assert {"emit", "mission", "Go", "Done", "Move"} <= set(items)
    close_document(client, document)
