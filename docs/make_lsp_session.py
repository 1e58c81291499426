"""Record a session of ``orccad lsp`` (docs/lsp-session.md): the messages an editor and the
server exchange on missions/false_property.orc — open (diagnostics), outline, hover on a
Robot-Task and on a law, go to definition, completion after ``law``, then a save and the
proof's verdicts, one of them false with its counterexample script.

Run from the repository root: ``python docs/make_lsp_session.py`` (needs the ``lsp`` extra).
Long lists in the answers (completion items, symbols) are cut to their first entries.
"""

from __future__ import annotations

import json
import os
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "bench"))

from _lsp_client import Client  # noqa: E402

MISSION = ROOT / "missions" / "false_property.orc"
OUT = ROOT / "docs" / "lsp-session.md"


def _shown(message: dict) -> dict:
    """``message`` with long lists cut and this machine's paths made relative."""
    text = json.dumps(message)
    text = text.replace(ROOT.as_uri() + "/", "file:///path/to/orccad/")
    shown = json.loads(text)
    result = shown.get("result")
    if isinstance(result, dict) and isinstance(result.get("items"), list) \
            and len(result["items"]) > 3:
        result["items"] = result["items"][:3] + [f"… {len(result['items']) - 3} more"]
    if isinstance(result, list) and len(result) > 3:
        shown["result"] = result[:3] + [f"… {len(result) - 3} more"]
    return shown


def _position(text: str, needle: str, offset: int = 0) -> dict:
    at = text.index(needle) + offset
    line = text.count("\n", 0, at)
    return {"line": line, "character": at - (text.rfind("\n", 0, at) + 1)}


def main() -> int:
    cache = tempfile.mkdtemp(prefix="orccad-lsp-session-")
    os.environ["XDG_CACHE_HOME"] = cache  # the counterexample scripts go there
    client = Client([sys.executable, "-m", "orccad_app", "lsp"])
    uri, text = MISSION.as_uri(), MISSION.read_text()
    doc = {"textDocument": {"uri": uri}}

    def request(method: str, params) -> dict:
        ident = client.send(method, params, request=True)
        return client.wait(lambda m: m.get("id") == ident)

    request("initialize", {"processId": os.getpid(), "rootUri": ROOT.as_uri(),
                           "capabilities": {"textDocument": {"completion": {
                               "completionItem": {"snippetSupport": True}}}}})
    client.send("initialized", {})
    client.send("textDocument/didOpen", {"textDocument": {
        "uri": uri, "languageId": "orccad", "version": 1, "text": text}})
    client.wait(lambda m: m.get("method") == "textDocument/publishDiagnostics")
    request("textDocument/documentSymbol", doc)
    request("textDocument/hover", {**doc, "position": _position(text, "run Approach", 4)})
    request("textDocument/hover", {**doc, "position": _position(text, "law pid", 4)})
    request("textDocument/definition", {**doc, "position": _position(text, "run Place", 4)})
    law = _position(text, "law pid", 4)
    request("textDocument/completion", {**doc, "position": law})
    client.send("textDocument/didSave", doc)
    client.wait(lambda m: m.get("method") == "textDocument/publishDiagnostics"
                and any(d.get("code") == "proof" for d in m["params"]["diagnostics"]))
    request("shutdown", None)
    client.send("exit", None)
    client.process.wait(timeout=30)
    lines = ["# A recorded `orccad lsp` session", "",
             "The messages between an editor and `orccad lsp` on "
             "`missions/false_property.orc`, recorded by `python docs/make_lsp_session.py` "
             "(long lists cut). `->` is the editor, `<-` the server.", ""]
    for direction, message in client.transcript:
        title = message.get("method") or f"response to request {message.get('id')}"
        lines += [f"**{direction} {title}**", "", "```json",
                  json.dumps(_shown(message), indent=2, ensure_ascii=False), "```", ""]
    OUT.write_text("\n".join(lines), encoding="utf-8")
    print(f"wrote {OUT.relative_to(ROOT)} ({len(client.transcript)} messages)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
