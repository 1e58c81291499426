"""Issue 34, item 17: docs/executive.md, docs/limits.md and docs/deploy.md agree with the
program: `orccad run`'s exit status when a property is false on a run that ends `done`, the
WebSocket subprotocol a Foxglove client must offer, `m->reason` and `enum orccad_role`."""

from __future__ import annotations

import re
import socket
import subprocess
import sys
import time
from pathlib import Path

import pytest

from tests.fuzz.harness import run_orccad

ROOT = Path(__file__).resolve().parents[2]
DOCS = ROOT / "docs"


def _read(name: str) -> str:
    return (DOCS / name).read_text(encoding="utf-8")


def test_a_property_false_on_a_done_run_exits_1_as_both_docs_say(tmp_path):
    text = (ROOT / "missions" / "arm_pid.orc").read_text(encoding="utf-8")
    path = tmp_path / "arm_pid.orc"
    path.write_text(text + "property ArmPID.tiny: always (norm(arm.e) < 0.0000001);\n",
                    encoding="utf-8")
    outcome = run_orccad(["run", str(path)], budget_s=120)
    assert "mission ArmPID: done" in outcome.out, outcome.out[:500]
    assert outcome.status == 1
    assert "orccad: property violated on this run: tiny" in outcome.err
    limits = _read("limits.md")
    row = next(line for line in limits.splitlines() if line.startswith("| 1 |"))
    assert "a property is false on the run even though the mission ended `done`" in row
    executive = " ".join(_read("executive.md").split())
    assert ("Exit status 1 for every status but `done`, and for a `done` run on which a "
            "property is false") in executive


def test_deploy_md_documents_reason_and_the_role_values_as_the_header_has_them(tmp_path):
    outcome = run_orccad(["codegen", str(ROOT / "missions" / "abro.orc"), "-o",
                          str(tmp_path)])
    assert outcome.status == 0, outcome.err
    header = next(tmp_path.glob("*.h")).read_text(encoding="utf-8")
    enum = re.search(r"enum orccad_role \{(.*?)\};", header, re.S).group(1)
    values = dict(re.findall(r"(ORCCAD_ROLE_\w+) = (\d+)", enum))
    deploy = _read("deploy.md")
    documented = dict(re.findall(r"^\| `(ORCCAD_ROLE_\w+)` \| (\d+) \|", deploy, re.M))
    assert documented == values
    assert "int reason; /* failed/aborted: the exception's name (string index), or -1 */" \
        in header
    prose = " ".join(deploy.split())
    assert ("`m->reason` (an `int`) is then the exception's name as an index into the string "
            "table, `PREFIX_string_names[m->reason]`") in prose


def _port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


def _offer(subprotocols: list[str]) -> str:
    """Start a short `orccad run --foxglove` and connect offering ``subprotocols``: the first
    message, or ``refused: …``."""
    from websockets.exceptions import InvalidStatus
    from websockets.sync.client import connect

    port = _port()
    mission = str(ROOT / "missions" / "arm_pid.orc")
    process = subprocess.Popen([sys.executable, "-m", "orccad_app.cli", "run", mission,
                                "--until", "0.2", "--foxglove", "--foxglove-port", str(port),
                                "--foxglove-wait", "5"],
                               stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    try:
        start = time.monotonic()
        while time.monotonic() - start < 90:
            assert process.poll() is None, process.communicate()[1]
            try:
                with connect(f"ws://127.0.0.1:{port}", open_timeout=2,
                             subprotocols=subprotocols or None) as ws:
                    return str(ws.recv(timeout=10))
            except InvalidStatus as refused:
                return f"refused: {refused.response.status_code}"
            except OSError:
                time.sleep(0.1)
        raise AssertionError("the Foxglove server did not come up")
    finally:
        process.kill()
        process.wait()


def test_a_foxglove_client_must_offer_the_subprotocol_the_doc_names():
    pytest.importorskip("foxglove")
    pytest.importorskip("websockets")
    doc = " ".join(_read("executive.md").split())
    assert "A client must offer the WebSocket subprotocol **`foxglove.sdk.v1`**" in doc
    assert '"op":"serverInfo"' in _offer(["foxglove.sdk.v1"])
    assert _offer(["foxglove.websocket.v1"]) == "refused: 400"
