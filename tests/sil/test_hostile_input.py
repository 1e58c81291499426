"""``orccad sil`` and ``orccad codegen`` on what a new user or a hostile input gives them: every
bad input is refused with a located message and exit status 2 before any work, nothing the
user wrote is overwritten, and an interrupted build leaves no process and no file behind.

The refusals run the command in this process (``orccad_app.cli.main``, fast: they come
before the controller is built); the interrupted builds run it in a subprocess (with a
timeout) with a stand-in compiler — a shell script with a child process and a temporary file,
as gcc's driver has ``cc1`` and its ``.s`` — so that no test waits for a real compilation.
"""

from __future__ import annotations

import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from orccad_app.cli import main
from orccad_app.sil.controller.process import ControllerProcess
from orccad_app.sil.build.compiler import BuildError, compiler_command

from tests.sil.helpers import MISSIONS

_TIMEOUT_S = 60


class _Done:
    def __init__(self, returncode: int, stderr: str) -> None:
        self.returncode, self.stderr = returncode, stderr


@pytest.fixture
def orccad(monkeypatch, capsys):
    """``orccad ARGS`` run in this process in folder ``cwd`` with ``env`` added: its exit
    status and standard error."""
    def run(*args: str, cwd: Path, env: dict[str, str] | None = None) -> _Done:
        with monkeypatch.context() as patch:
            patch.chdir(cwd)
            for name, value in (env or {}).items():
                patch.setenv(name, value)
            status = main(list(args))
        return _Done(status, capsys.readouterr().err)
    return run


@pytest.fixture
def recovery(tmp_path: Path) -> Path:
    """A copy of ``arm_recovery.orc`` with the library it imports, and an input script."""
    shutil.copy(MISSIONS / "arm_recovery.orc", tmp_path)
    shutil.copytree(MISSIONS / "lib", tmp_path / "lib")
    (tmp_path / "stop.in").write_text("@0.2 Stop\n")
    return tmp_path


@pytest.mark.parametrize("command,target", [
    (("sil", "--lockstep"), "lib/homing.orc"),       # a file the mission imports
    (("sil", "--lockstep"), "stop.in"),              # the --inject-from script
    (("run",), "lib/homing.orc"),
])
def test_the_trace_never_overwrites_an_input_of_the_run(orccad, recovery, command, target):
    before = (recovery / target).read_bytes()
    done = orccad(*command, "arm_recovery.orc", "--until", "0.1", "--inject-from", "stop.in",
                   "--trace", target, "--trace-format", "csv", cwd=recovery)
    assert done.returncode == 2, done.stderr
    assert (f"{target}: refusing to overwrite the input file {target} (choose another "
            "--trace)") in done.stderr
    assert (recovery / target).read_bytes() == before


def test_a_build_dir_holding_the_users_files_is_refused_and_left_untouched(orccad, tmp_path):
    shutil.copy(MISSIONS / "arm_pid.orc", tmp_path)
    mine = tmp_path / "mine"
    mine.mkdir()
    (mine / "orccad_modules.c").write_text("/* my own table, hand-written */\n")
    (mine / "orccad_io.c").write_text("/* my robot's drivers */\n")
    done = orccad("sil", "arm_pid.orc", "--lockstep", "--build-dir", "mine", cwd=tmp_path)
    assert done.returncode == 2, done.stderr
    assert ("--build-dir mine: the folder holds files the SIL build did not write "
            "(orccad_io.c, orccad_modules.c)") in done.stderr
    assert sorted(p.name for p in mine.iterdir()) == ["orccad_io.c", "orccad_modules.c"]
    assert (mine / "orccad_modules.c").read_text() == "/* my own table, hand-written */\n"


@pytest.mark.parametrize("flag,value,words", [
    ("--build-dir", "notes.txt", "--build-dir notes.txt: exists and is not a folder"),
    ("--build-dir", "", "--build-dir: an empty name"),
    ("--inject-from", "", "--inject-from: an empty name"),
    ("--trace", " ", "--trace: an empty name"),
])
def test_a_bad_or_empty_output_name_is_refused(orccad, tmp_path, flag, value, words):
    shutil.copy(MISSIONS / "arm_pid.orc", tmp_path)
    (tmp_path / "notes.txt").write_text("mine\n")
    done = orccad("sil", "arm_pid.orc", "--lockstep", flag, value, cwd=tmp_path)
    assert done.returncode == 2, done.stderr
    assert words in done.stderr
    assert (tmp_path / "notes.txt").read_text() == "mine\n"


@pytest.mark.parametrize("command", ["sil", "run"])
def test_a_trace_onto_a_fifo_is_refused_not_waited_on(tmp_path, command):
    shutil.copy(MISSIONS / "arm_pid.orc", tmp_path)
    os.mkfifo(tmp_path / "pipe")  # no reader: opening it to write would wait forever
    mode = ("--lockstep",) if command == "sil" else ()
    done = subprocess.run([sys.executable, "-m", "orccad_app", command, "arm_pid.orc", *mode,
                           "--trace", "pipe", "--trace-format", "csv"], cwd=tmp_path,
                          capture_output=True, text=True, timeout=30)
    assert done.returncode == 2, done.stderr
    assert "--trace pipe: a FIFO, not a regular file" in done.stderr


def test_a_build_dir_a_previous_build_wrote_is_regenerated(orccad, tmp_path):
    shutil.copy(MISSIONS / "arm_pid.orc", tmp_path)
    for _ in range(2):
        done = orccad("sil", "arm_pid.orc", "--lockstep", "--until", "0.01",
                       "--build-dir", "build/arm", cwd=tmp_path)
        assert done.returncode == 1 and "mission timeout" in done.stderr, done.stderr
    assert sorted(p.name for p in (tmp_path / "build" / "arm").iterdir()) == [
        "orc_mission.c", "orc_mission.h", "orccad_automaton_binding.h", "orccad_modules.c",
        "plugin_orccad_obs_joint_limits.c"]  # the observers' plugin's C, copied once


def test_cc_is_a_command_and_a_bad_one_is_named(monkeypatch):
    monkeypatch.setenv("CC", "sh -c")
    assert compiler_command() == [shutil.which("sh"), "-c"]
    monkeypatch.setenv("CC", 'gcc "-O2')
    with pytest.raises(BuildError, match="CC='gcc \"-O2': cannot be read as a command"):
        compiler_command()


def test_a_failing_compiler_and_an_unusable_cache_are_named(orccad, tmp_path):
    shutil.copy(MISSIONS / "arm_pid.orc", tmp_path)
    cache = tmp_path / "cache"
    done = orccad("sil", "arm_pid.orc", "--lockstep", cwd=tmp_path,
                   env={"CC": "false", "ORCCAD_CACHE_DIR": str(cache)})
    assert done.returncode == 2, done.stderr
    assert "the controller does not compile (" in done.stderr
    assert "false: exit status 1, no message)" in done.stderr
    assert list((cache / "sil").iterdir()) == []  # no empty folder of a failed build
    (tmp_path / "afile").write_text("")
    done = orccad("sil", "arm_pid.orc", "--lockstep", cwd=tmp_path,
                   env={"ORCCAD_CACHE_DIR": str(tmp_path / "afile")})
    assert done.returncode == 2, done.stderr
    assert (f"ORCCAD_CACHE_DIR={tmp_path / 'afile'}: cannot hold the compiled controller"
            in done.stderr)
    assert "Not a directory" in done.stderr


_FAKE_CC = """#!/bin/sh
# A compiler that takes long: a child process (gcc's cc1) and a temporary file in $TMPDIR.
touch "$TMPDIR/cc-partial.s"
sleep {marker} &
echo started > "{started}"
wait
"""


def _processes_with(marker: str) -> list[int]:
    found = []
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                words = (entry / "cmdline").read_bytes().split(b"\0")
                state = (entry / "stat").read_text().rsplit(")", 1)[1].split()[0]
            except OSError:
                continue
            if marker.encode() in words and state != "Z":
                found.append(int(entry.name))
    return found


@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGTERM])
def test_an_interrupted_build_leaves_no_process_and_no_file(tmp_path, signum):
    shutil.copy(MISSIONS / "arm_pid.orc", tmp_path)
    marker = f"9{os.getpid() % 100}.{signum}7"  # sleep's argument: unique to this test
    started = tmp_path / "started"
    fake = tmp_path / "slow-cc"
    fake.write_text(_FAKE_CC.format(marker=marker, started=started))
    fake.chmod(0o755)
    temporary, cache = tmp_path / "tmp", tmp_path / "cache"
    temporary.mkdir()
    command = subprocess.Popen(
        [sys.executable, "-m", "orccad_app", "sil", "arm_pid.orc", "--lockstep"], cwd=tmp_path,
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
        env={**os.environ, "CC": str(fake), "TMPDIR": str(temporary),
             "ORCCAD_CACHE_DIR": str(cache)})
    try:
        deadline = time.monotonic() + _TIMEOUT_S
        while not started.exists() and time.monotonic() < deadline:
            time.sleep(0.02)
        assert started.exists(), "the compiler did not start"
        command.send_signal(signum)
        _, err = command.communicate(timeout=_TIMEOUT_S)
    finally:
        command.kill()
        command.wait()
    assert command.returncode == 130, err
    assert "orccad: interrupted" in err
    assert _processes_with(marker) == []  # the compiler's child went with it
    assert list(temporary.iterdir()) == []  # the scratch folder of the emitted C too
    assert [p for p in cache.rglob("*") if p.name != "sil"] == []  # nor a partial build


def test_codegen_refuses_an_empty_output_name_and_a_folder_in_the_way(orccad, tmp_path):
    shutil.copy(MISSIONS / "abro.orc", tmp_path)
    done = orccad("codegen", "abro.orc", "-o", "", cwd=tmp_path)
    assert done.returncode == 2 and "-o/--output: an empty name" in done.stderr, done.stderr
    assert not (tmp_path / "abro").exists()
    (tmp_path / "out" / "abro.c").mkdir(parents=True)  # a folder named as a generated file
    (tmp_path / "out" / "abro.c" / "keep.txt").write_text("mine\n")
    done = orccad("codegen", "abro.orc", "-o", "out", cwd=tmp_path)
    assert done.returncode == 2, done.stderr
    assert "out: the output folder holds other files (abro.c)" in done.stderr
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == ["abro.c"]
    assert (tmp_path / "out" / "abro.c" / "keep.txt").read_text() == "mine\n"


def test_ctrl_c_while_a_controller_starts_leaves_no_process(tmp_path):
    # a controller hung before its first answer, in its own session (Ctrl-C at the terminal
    # does not reach it) and not reading its socket: only the plant server can end it
    marker = f"8{os.getpid() % 100}.25"
    hung = tmp_path / "hung-controller"
    hung.write_text(f"#!/bin/sh\nexec sleep {marker}\n")
    hung.chmod(0o755)

    def interrupt(signum, frame):
        raise KeyboardInterrupt

    previous = signal.signal(signal.SIGALRM, interrupt)
    signal.setitimer(signal.ITIMER_REAL, 0.5)
    try:
        with pytest.raises(KeyboardInterrupt):
            ControllerProcess(hung, 1, "digest", heartbeat_s=30.0)
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)
    assert _processes_with(marker) == []


def test_a_run_past_its_budget_is_refused_before_the_controller_is_built(orccad, tmp_path):
    """The run's cost (reactions and jobs over --until) is checked before the controller's
    C is generated and compiled: nothing lands in the build cache."""
    cache = tmp_path / "cache"
    done = orccad("sil", str(MISSIONS / "arm_pid.orc"), "--lockstep", "--until", "10000",
                  "--timing", "TrackPID.ctrl.period_ms=0.001", cwd=tmp_path,
                  env={"ORCCAD_CACHE_DIR": str(cache)})
    assert done.returncode == 2 and "would cost up to" in done.stderr, done.stderr
    assert not cache.exists() or not any(cache.rglob("orccad_controller*"))
