"""The language server under test: ``orccad lsp`` as a subprocess, driven by pytest-lsp.

Each test module opens one session (module-scoped) to keep the suite fast; tests open their
own documents (files under ``tmp_path_factory`` or the shipped missions) in it.
"""

from __future__ import annotations

import asyncio
import os
import sys
from pathlib import Path

import pytest

pytest.importorskip("pytest_lsp")

from lsprotocol import types  # noqa: E402
from pytest_lsp import ClientServerConfig, LanguageClient  # noqa: E402
from pytest_lsp.client import make_test_lsp_client  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
MISSIONS = ROOT / "missions"

#: The server command: the real CLI, no debounce beyond the default.
SERVER = [sys.executable, "-m", "orccad_app", "lsp"]


def uri(path: Path | str) -> str:
    return Path(path).resolve().as_uri()


async def initialize(client: LanguageClient) -> None:
    await client.initialize_session(types.InitializeParams(
        capabilities=types.ClientCapabilities(),
        root_uri=uri(ROOT),
        workspace_folders=[types.WorkspaceFolder(uri=uri(ROOT), name="orccad")]))


def make_client() -> LanguageClient:
    """pytest-lsp's client, also recording every publication of diagnostics with its
    document version in ``client.published`` (to wait for the one of a given version, not a
    stale one, such as the clearing that follows a close)."""
    client = make_test_lsp_client()
    client.published = []
    recorder = client.protocol.fm._features[types.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS]

    def record(params: types.PublishDiagnosticsParams) -> None:
        client.published.append(params)
        recorder(params)

    client.protocol.fm._features[types.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS] = record
    return client


def config(**extra) -> ClientServerConfig:
    """The server under test, with this module's client."""
    return ClientServerConfig(server_command=SERVER, client_factory=make_client, **extra)


async def diagnostics_of(client: LanguageClient, target: str, version: int | None = None,
                         since: int = 0, timeout_s: float = 60.0) -> list[types.Diagnostic]:
    """The diagnostics of ``target`` published after ``client.published[since]`` (for
    document ``version`` when given), waiting for them."""
    async def arrived():
        while True:
            for params in client.published[since:]:
                if params.uri == target and (version is None or params.version == version):
                    return list(params.diagnostics)
            await asyncio.sleep(0.01)
    return await asyncio.wait_for(arrived(), timeout_s)


async def open_document(client: LanguageClient, path: Path | str, text: str | None = None,
                        version: int = 1, timeout_s: float = 60.0) -> list[types.Diagnostic]:
    """Open ``path`` (with ``text``, else its content) and wait for its diagnostics."""
    target = uri(path)
    since = len(client.published)
    client.text_document_did_open(types.DidOpenTextDocumentParams(
        types.TextDocumentItem(uri=target, language_id="orccad", version=version,
                               text=Path(path).read_text() if text is None else text)))
    return await diagnostics_of(client, target, version, since, timeout_s)


async def change_document(client: LanguageClient, path: Path | str, text: str,
                          version: int) -> list[types.Diagnostic]:
    """Replace the whole text of ``path`` and wait for its new diagnostics."""
    target = uri(path)
    since = len(client.published)
    client.text_document_did_change(types.DidChangeTextDocumentParams(
        text_document=types.VersionedTextDocumentIdentifier(uri=target, version=version),
        content_changes=[types.TextDocumentContentChangeWholeDocument(text=text)]))
    return await diagnostics_of(client, target, version, since)


def close_document(client: LanguageClient, path: Path | str) -> None:
    client.text_document_did_close(types.DidCloseTextDocumentParams(
        types.TextDocumentIdentifier(uri=uri(path))))


def server_env(**extra: str) -> dict[str, str]:
    env = dict(os.environ)
    env.update(extra)
    return env
