"""``orccad lsp`` as a command: without the extra it exits 2 naming what to install."""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
import time

from tests.lsp.conftest import ROOT


def test_orccad_lsp_without_the_extra_exits_2_naming_what_to_install(tmp_path):
    # a path entry that makes `import pygls` fail, as on an install without the extra
    (tmp_path / "pygls").mkdir()
    (tmp_path / "pygls" / "__init__.py").write_text("raise ImportError('no pygls here', "
                                                    "name='pygls')\n")
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(tmp_path), str(ROOT)])}
    done = subprocess.run([sys.executable, "-m", "orccad_app", "lsp"], capture_output=True,
                          text=True, env=env, timeout=60, stdin=subprocess.DEVNULL)
    assert done.returncode == 2
    assert "pip install 'orccad[lsp]'" in done.stderr
    assert "Traceback" not in done.stderr


def _send(process, message: dict) -> None:
    body = json.dumps({"jsonrpc": "2.0", **message}).encode()
    process.stdin.write(f"Content-Length: {len(body)}\r\n\r\n".encode() + body)
    process.stdin.flush()


def _receive(process) -> dict:
    length = 0
    while (line := process.stdout.readline()) not in (b"\r\n", b"\n", b""):
        if line.lower().startswith(b"content-length:"):
            length = int(line.split(b":")[1])
    return json.loads(process.stdout.read(length))


def test_an_editor_that_goes_away_leaves_no_server_and_no_proof_behind(tmp_path):
    """stdin closed (the editor crashed) in the middle of a proof: the server exits and kills
    the proof's process."""
    mission = ROOT / "missions" / "arm_recovery.orc"
    env = {**os.environ, "XDG_CACHE_HOME": str(tmp_path)}
    process = subprocess.Popen([sys.executable, "-m", "orccad_app", "lsp"], cwd=ROOT, env=env,
                               stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                               stderr=subprocess.DEVNULL)
    try:
        _send(process, {"id": 1, "method": "initialize",
                        "params": {"processId": None, "rootUri": None, "capabilities": {}}})
        while _receive(process).get("id") != 1:
            pass
        _send(process, {"method": "initialized", "params": {}})
        _send(process, {"method": "textDocument/didOpen", "params": {"textDocument": {
            "uri": mission.as_uri(), "languageId": "orccad", "version": 1,
            "text": mission.read_text()}}})
        while _receive(process).get("method") != "textDocument/publishDiagnostics":
            pass
        _send(process, {"method": "textDocument/didSave",
                        "params": {"textDocument": {"uri": mission.as_uri()}}})
        while True:
            message = _receive(process)
            started = re.search(r"proof of .* started \(process (\d+)\)",
                                message.get("params", {}).get("message", ""))
            if message.get("method") == "window/logMessage" and started:
                break
        proof = int(started.group(1))
        process.stdin.close()
        assert process.wait(timeout=60) == 0
        for _ in range(100):
            try:
                os.kill(proof, 0)
            except ProcessLookupError:
                break
            time.sleep(0.05)
        else:
            raise AssertionError(f"the proof's process {proof} outlived the server")
    finally:
        if process.poll() is None:
            process.kill()
            process.wait()
