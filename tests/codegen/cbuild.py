"""Compiling generated C in tests: the strict flags, one build per content, cached in tmp.

:func:`build` writes a generated program's files (and ``PREFIX_main.c``) to a folder named
by the SHA-256 of their text, the flags and the compiler, under the system's temporary folder,
and compiles them there once: a test session (or the next one) that generates the same C
reuses the binary. Tests skip, saying why, where no C compiler exists.
"""

from __future__ import annotations

import hashlib
import json
import os
import shutil
import subprocess
import tempfile
from pathlib import Path

import pytest

from orccad_app.codegen.driver import main_source
from orccad_app.codegen.generate import CProgram

__all__ = ["STRICT", "SANITIZE", "compiler", "build", "run_trace", "run_lines", "run_traces"]

#: the flags the issue asks every generated file to pass
STRICT = ("-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic")
#: undefined behaviour and memory errors abort the program
SANITIZE = ("-fsanitize=undefined,address", "-fno-sanitize-recover=all", "-g")
CACHE = Path(tempfile.gettempdir()) / "orccad-codegen-cache"


def compiler() -> str:
    """The C compiler (``$CC``, gcc or cc); skips the test when there is none."""
    for name in (os.environ.get("CC"), "gcc", "cc"):
        if name and shutil.which(name):
            return name
    pytest.skip("no C compiler (gcc or cc) on this machine: the generated C is not compiled")


def build(program: CProgram, flags: tuple[str, ...] = STRICT + ("-O1",),
          with_main: bool = True) -> Path:
    """The compiled ``PREFIX_main`` of ``program`` (compiled once per content)."""
    cc = compiler()
    files = dict(program.files)
    if with_main:
        files[f"{program.prefix}_main.c"] = main_source(program)
    key = hashlib.sha256(json.dumps([cc, flags, sorted(files.items())]).encode()).hexdigest()
    folder = CACHE / key[:24]
    binary = folder / program.prefix
    if binary.exists():
        return binary
    staging = Path(tempfile.mkdtemp(prefix="build.", dir=_cache()))
    for name, text in files.items():
        (staging / name).write_text(text, encoding="utf-8")
    sources = [name for name in files if name.endswith(".c")]
    done = subprocess.run([cc, *flags, "-o", program.prefix, *sources], cwd=staging,
                          capture_output=True, text=True, timeout=300)
    if done.returncode != 0:
        raise AssertionError(f"{cc} {' '.join(flags)} failed on {program.prefix}:\n"
                             f"{done.stderr[:4000]}")
    try:
        os.rename(staging, folder)
    except OSError:  # another process built it first
        shutil.rmtree(staging, ignore_errors=True)
    return binary


def _cache() -> Path:
    CACHE.mkdir(parents=True, exist_ok=True)
    return CACHE


def run_trace(binary: Path, script: Path) -> tuple[list[dict], int, str]:
    """The records ``binary SCRIPT --trace`` prints, its exit status and its stderr."""
    lines, status, stderr = run_lines(binary, script)
    return [json.loads(line) for line in lines], status, stderr


def run_lines(binary: Path, script: Path) -> tuple[list[str], int, str]:
    """The lines ``binary SCRIPT --trace`` prints (as text), its exit status and stderr."""
    done = subprocess.run([str(binary), str(script), "--trace"], capture_output=True,
                          text=True, timeout=120)
    return done.stdout.splitlines(), done.returncode, done.stderr


def run_traces(binary: Path, scripts: list[Path]) -> dict[str, list[dict]]:
    """The records of each script, run in one process (``--trace S1 S2 …``), by path."""
    found: dict[str, list[dict]] = {}
    for first in range(0, len(scripts), 200):  # keep the command line short
        done = subprocess.run([str(binary), "--trace", *map(str, scripts[first:first + 200])],
                              capture_output=True, text=True, timeout=300)
        current: list[dict] = []
        for line in done.stdout.splitlines():
            record = json.loads(line)
            if "script" in record:
                current = found.setdefault(record["script"], [])
            else:
                current.append(record)
        assert done.returncode in (0, 1, 2), done.stderr[-2000:]
    return found
