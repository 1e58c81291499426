"""The project's own build step of the controller process: C99 sources → one executable.

No network and no build system: the C compiler (``$CC``, split as a shell does, e.g. ``ccache
gcc``; else ``cc``) compiles the generated table and the runtime library (``orccad_app/sil/c``)
with ``-std=c99 -Wall -Wextra -Werror -pedantic`` (and ``$ORCCAD_SIL_CFLAGS``, e.g.
``-fsanitize=thread -g``). The executable is cached under ``$ORCCAD_CACHE_DIR`` (default
``~/.cache/orccad``) by a hash of its sources, flags and compiler, so that a mission is
compiled once; a missing compiler, an unusable cache folder or a failing compilation is a
:class:`BuildError` naming it (with the compiler's message and exit status).

The compiler runs in its own process group with its temporary files in the build's own
temporary folder: however the build ends (a failure, its time budget, Ctrl-C or SIGTERM turned
into an exception), the whole group (the driver and ``cc1``, ``as``, ``ld``) is ended and
reaped and nothing of it is left on disk.
"""

from __future__ import annotations

import hashlib
import os
import shlex
import shutil
import signal
import subprocess
import tempfile
from pathlib import Path

from orccad_app.diagnostics import OrccadError
from orccad_app.sil.generate.library import C_DIR

__all__ = ["BuildError", "CFLAGS", "build_executable", "compiler", "compiler_command",
           "extra_flags"]

CFLAGS = ("-std=c99", "-O2", "-Wall", "-Wextra", "-Werror", "-pedantic")
_BUILD_TIMEOUT_S = 120.0
_STOP_GRACE_S = 1.0
"""How long the compiler's group has after SIGTERM (to remove its files) before SIGKILL [s]."""
_MESSAGE_LINES = 60
"""The compiler's message is cut after this many lines."""


class BuildError(OrccadError):
    """The controller could not be built (no C compiler, or it failed)."""


def compiler_command() -> list[str]:
    """The C compiler's command: ``$CC`` split as a shell does (``ccache gcc``, ``gcc -m32``),
    its program resolved on ``PATH``, else ``cc``, else ``gcc``; raises :class:`BuildError`
    when none is found or ``$CC`` cannot be read."""
    text = os.environ.get("CC", "").strip()
    if text:
        try:
            words = shlex.split(text)
        except ValueError as error:
            raise BuildError(f"CC={text!r}: cannot be read as a command ({error})") from None
        found = shutil.which(words[0]) if words else None
        if found is None:
            raise BuildError(f"orccad sil needs a C compiler: CC={text!r}: {words[0]!r} not "
                             f"found (install gcc, e.g. apt-get install -y gcc, or set CC)")
        return [found, *words[1:]]
    for name in ("cc", "gcc"):
        found = shutil.which(name)
        if found is not None:
            return [found]
    raise BuildError("orccad sil needs a C compiler: cc or gcc not found (install gcc, e.g. "
                     "apt-get install -y gcc, or set CC)")


def compiler() -> str:
    """The C compiler's path (the program of :func:`compiler_command`)."""
    return compiler_command()[0]


def extra_flags() -> tuple[str, ...]:
    """The compiler flags added by ``$ORCCAD_SIL_CFLAGS`` (e.g. ``-fsanitize=thread -g`` to run
    the controller under ThreadSanitizer), split as a shell does."""
    text = os.environ.get("ORCCAD_SIL_CFLAGS", "")
    try:
        return tuple(shlex.split(text))
    except ValueError as error:
        raise BuildError(f"ORCCAD_SIL_CFLAGS={text!r}: cannot be read as flags "
                         f"({error})") from None


def _cache_dir() -> Path:
    root = os.environ.get("ORCCAD_CACHE_DIR")
    return Path(root) if root else Path.home() / ".cache" / "orccad"


def _cache_name() -> str:
    root = os.environ.get("ORCCAD_CACHE_DIR")
    return f"ORCCAD_CACHE_DIR={root}" if root else f"the cache folder {_cache_dir()} (set " \
        "ORCCAD_CACHE_DIR to choose another)"


def build_executable(sources: list[Path], name: str = "orccad_controller",
                     libraries: tuple[str, ...] = ("-lm",)) -> Path:
    """Compile ``sources`` (with the runtime library's folder and every source's folder on the
    include path: the generated headers sit beside the generated sources) into one
    executable, cached by content (the sources and every header of those folders); return its
    path."""
    cc = compiler_command()
    flags = (*CFLAGS, *extra_flags())
    folders = list(dict.fromkeys([C_DIR, *(path.parent for path in sources)]))
    digest = hashlib.sha256()
    for part in (*cc, *flags, *libraries):
        digest.update(part.encode() + b"\0")
    headers = [header for folder in folders for header in sorted(folder.glob("*.h"))]
    for path in [*sources, *headers]:
        digest.update(path.name.encode() + b"\0" + path.read_bytes() + b"\0")
    target_dir = _cache_dir() / "sil" / digest.hexdigest()[:24]
    target = target_dir / name
    if target.exists():
        return target
    try:
        target_dir.mkdir(parents=True, exist_ok=True)
        work_dir = tempfile.TemporaryDirectory(dir=target_dir)
    except OSError as error:
        raise BuildError(f"{_cache_name()}: cannot hold the compiled controller: "
                         f"{error.filename}: {error.strerror or error}") from None
    try:
        with work_dir as work:
            partial = Path(work) / name
            includes = [part for folder in folders for part in ("-I", str(folder))]
            command = [*cc, *flags, *includes, *map(str, sources), "-o", str(partial),
                       *libraries]
            _compile(command, work)
            os.replace(partial, target)  # atomic: a concurrent build finds a whole file or none
    finally:
        if not target.exists():
            try:
                target_dir.rmdir()  # a failed build leaves no empty folder (a busy one stays)
            except OSError:
                pass
    return target


def _compile(command: list[str], work: str) -> None:
    """Run the compiler ``command`` in its own process group, its temporary files in
    ``work``; raise :class:`BuildError` when it fails or takes too long. However this ends
    (an exception included: Ctrl-C), the group is ended and reaped."""
    try:
        process = subprocess.Popen(command, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                                   stderr=subprocess.STDOUT, text=True, errors="replace",
                                   start_new_session=True, env={**os.environ, "TMPDIR": work})
    except OSError as error:
        raise BuildError(f"the C compiler {command[0]} could not start: "
                         f"{error.strerror or error}") from None
    try:
        message, _ = process.communicate(timeout=_BUILD_TIMEOUT_S)
    except BaseException as error:  # its time budget, Ctrl-C, SIGTERM: end the whole group
        _end_group(process)
        if isinstance(error, subprocess.TimeoutExpired):
            raise BuildError(f"the C compiler took more than {_BUILD_TIMEOUT_S:g} s") from None
        raise
    if process.returncode != 0:
        lines = message.strip().splitlines()
        shown = "\n".join(lines[:_MESSAGE_LINES]) + (f"\n… ({len(lines) - _MESSAGE_LINES} more "
                                                    "lines)" if len(lines) > _MESSAGE_LINES
                                                    else "")
        status = (f"killed by signal {-process.returncode}" if process.returncode < 0
                  else f"exit status {process.returncode}")
        raise BuildError(f"the controller does not compile ({command[0]}: {status}"
                         + ("):\n" + shown if shown else ", no message)"))


def _end_group(process: subprocess.Popen) -> None:
    """End the compiler's process group — SIGTERM (gcc's driver removes its files), then
    SIGKILL for what did not end — and reap the compiler."""
    for sent in (signal.SIGTERM, signal.SIGKILL):
        try:
            os.killpg(process.pid, sent)
        except ProcessLookupError:  # the group has ended
            pass
        try:
            process.wait(timeout=_STOP_GRACE_S)
        except subprocess.TimeoutExpired:
            pass
    if process.stdout is not None:
        process.stdout.close()
    process.wait()
