"""The top-level guard of ``orccad``: internal errors (exit 3), Ctrl-C (130), a plugin calling
sys.exit, full disks and unreadable input — never a traceback by default (issue 12)."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
from pathlib import Path

import pytest

from orccad_app import cli
from orccad_app.cli import main
from tests.plugins.conftest import install_dist_info

ROOT = Path(__file__).resolve().parents[1]
ABRO = str(ROOT / "missions" / "abro.orc")
FULL = Path("/dev/full")
needs_dev_full = pytest.mark.skipif(not FULL.exists(), reason="needs /dev/full")


def orccad(*args: str, env: dict | None = None, **options) -> subprocess.CompletedProcess:
    environment = {k: v for k, v in os.environ.items() if k != cli.DEBUG_ENV}
    environment.update(env or {})
    options.setdefault("stdout", subprocess.PIPE)
    return subprocess.run([sys.executable, "-m", "orccad_app.cli", *args],
                          stderr=subprocess.PIPE, text=True, cwd=ROOT, env=environment,
                          **options)


@pytest.fixture
def crashing_compile(monkeypatch):
    """``orccad compile`` whose implementation has a bug (an unexpected exception)."""
    from orccad_app.commands import compile as command

    def broken(args):
        return 1 / 0
    monkeypatch.setattr(command, "run", broken)
    monkeypatch.delenv(cli.DEBUG_ENV, raising=False)


def test_an_unexpected_exception_is_an_internal_error_with_status_3(crashing_compile, capsys):
    assert main(["compile", ABRO]) == cli.EXIT_INTERNAL == 3
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err
    assert "internal error (ZeroDivisionError: division by zero)" in err
    assert "please report it" in err and "--debug" in err


@pytest.mark.parametrize("where", ["after", "before"])
def test_debug_flag_shows_the_traceback(crashing_compile, capsys, where):
    argv = ["compile", ABRO, "--debug"] if where == "after" else ["--debug", "compile", ABRO]
    assert main(argv) == 3
    assert "Traceback" in capsys.readouterr().err


def test_debug_environment_variable_shows_the_traceback(crashing_compile, capsys, monkeypatch):
    monkeypatch.setenv(cli.DEBUG_ENV, "1")
    assert main(["compile", ABRO]) == 3
    assert "Traceback" in capsys.readouterr().err


def test_a_plugin_calling_sys_exit_is_disabled_by_name_and_the_command_goes_on(tmp_path):
    # issue 28: a plugin's sys.exit during import is reported and disabled like one that
    # raises (it used to end every command with exit 3 "this is a bug")
    site = tmp_path / "site"
    site.mkdir()
    (site / "exiting_plugin.py").write_text("import sys\nsys.exit(7)\n")
    install_dist_info(site, "exiting-plugin", "1.0", {"exiting": "exiting_plugin"})
    result = orccad("compile", "missions/arm_pid.orc",
                    env={"PYTHONPATH": str(site), "ORCCAD_DISABLE_PLUGINS": ""})
    assert result.returncode == 0, result.stderr
    assert "plugin 'exiting' disabled" in result.stderr and "sys.exit(7)" in result.stderr
    assert "Traceback" not in result.stderr
    assert "states" in result.stdout


def test_ctrl_c_during_the_imports_exits_130_without_traceback():
    # -X importtime reports each import as it ends: interrupt right after the CLI module is
    # imported, while the compiler's modules (lark, the reactive layer) are being imported.
    process = subprocess.Popen([sys.executable, "-X", "importtime", "-m", "orccad_app.cli",
                                "compile", ABRO], cwd=ROOT, stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True)
    seen = []
    for line in process.stderr:
        seen.append(line)
        if line.rstrip().endswith("orccad_app.commands.arguments"):
            process.send_signal(signal.SIGINT)
            break
    rest = process.stderr.read()
    process.wait(timeout=60)
    assert process.returncode == 130, rest
    assert "Traceback" not in rest and "orccad: interrupted" in rest


def test_ctrl_c_in_a_command_exits_130(monkeypatch, capsys):
    from orccad_app.commands import compile as command

    def interrupted(args):
        raise KeyboardInterrupt
    monkeypatch.setattr(command, "run", interrupted)
    assert main(["compile", ABRO]) == 130
    assert "interrupted" in capsys.readouterr().err


@needs_dev_full
@pytest.mark.parametrize("command", [["compile", ABRO], ["check", ABRO],
                                     ["react", ABRO, "--inputs", "missions/abro.in"],
                                     ["plugins", "--json"]])
def test_standard_output_on_a_full_disk_is_a_clear_error(command):
    with open(FULL, "w") as full:
        result = orccad(*command, stdout=full)
    assert result.returncode == 2
    assert "No space left on device" in result.stderr and "Traceback" not in result.stderr
    assert "Exception ignored" not in result.stderr


@needs_dev_full
def test_output_file_on_a_full_disk_is_a_clear_error():
    result = orccad("compile", ABRO, "-o", str(FULL))
    assert result.returncode == 2 and "/dev/full: cannot write" in result.stderr


@needs_dev_full
@pytest.mark.parametrize("suffix", [".csv", ".mcap"])
def test_trace_on_a_full_disk_is_a_clear_error(tmp_path, suffix):
    trace = tmp_path / f"full{suffix}"
    trace.symlink_to(FULL)
    result = orccad("run", "missions/arm_pid.orc", "--until", "0.2", "--trace", str(trace))
    assert result.returncode == 2, result.stderr
    assert f"full{suffix}: cannot write the trace: No space left" in result.stderr
    assert "Traceback" not in result.stderr


def test_a_closed_pipe_is_not_an_error():
    process = subprocess.Popen([sys.executable, "-m", "orccad_app.cli", "compile", ABRO,
                                "--format", "dot"], cwd=ROOT, stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE)
    process.stdout.close()
    _, err = process.communicate(timeout=60)
    assert b"Traceback" not in err and process.returncode == 0


def test_a_source_that_is_not_utf8_is_a_located_error(tmp_path, capsys):
    bad = tmp_path / "latin1.orc"
    bad.write_bytes(b"mission M {\n  output O; // caf\xe9\n  emit O;\n}\n")
    assert main(["compile", str(bad)]) == 2
    err = capsys.readouterr().err
    assert f"{bad}:2:19: error: not UTF-8 text: byte 0xe9" in err


def test_a_script_that_is_not_utf8_is_a_located_error(tmp_path, capsys):
    script = tmp_path / "s.in"
    script.write_bytes(b"A\nB \xff\n")
    assert main(["react", ABRO, "--inputs", str(script)]) == 2
    assert f"{script}:2:3: error: not UTF-8 text: byte 0xff" in capsys.readouterr().err


def test_a_folder_or_a_missing_file_is_bad_input(tmp_path, capsys):
    assert main(["compile", str(tmp_path)]) == 2
    assert main(["compile", str(tmp_path / "nope.orc")]) == 2
    err = capsys.readouterr().err
    assert "is a folder" in err and "no such file" in err and "Traceback" not in err


def test_a_huge_source_is_refused_at_once(tmp_path, capsys):
    from orccad_app.pipeline import MAX_SOURCE_BYTES

    big = tmp_path / "big.orc"
    line = "mission M { output O; emit O; }\n"
    big.write_text(line * (5_000_000 // len(line)))
    assert main(["compile", str(big)]) == 2
    assert f"larger than the {MAX_SOURCE_BYTES} bytes" in capsys.readouterr().err
