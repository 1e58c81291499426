"""The project's own build step of the controller process: C99 sources → one executable.

No network and no build system: the C compiler (``$CC``, else ``cc``) compiles the generated
table and the runtime library (``orccad_app/sil/c``) with ``-std=c99 -Wall -Wextra -Werror
-pedantic`` (and ``$ORCCAD_SIL_CFLAGS``, e.g. ``-fsanitize=thread -g``). The executable is
cached under ``$ORCCAD_CACHE_DIR`` (default ``~/.cache/orccad``) by a hash of its sources,
flags and compiler, so that a mission is compiled once; a missing compiler or a failing
compilation is an :class:`BuildError` with the compiler's message.
"""

from __future__ import annotations

import hashlib
import os
import shutil
import subprocess
import tempfile
from pathlib import Path

from orccad_app.diagnostics import OrccadError

__all__ = ["BuildError", "C_DIR", "CFLAGS", "library_sources", "build_executable", "compiler",
           "extra_flags"]

C_DIR = Path(__file__).parent / "c"
"""The runtime library's sources."""
CFLAGS = ("-std=c99", "-O2", "-Wall", "-Wextra", "-Werror", "-pedantic")
_BUILD_TIMEOUT_S = 120.0


class BuildError(OrccadError):
    """The controller could not be built (no C compiler, or it failed)."""


def library_sources(main: str = "orccad_lockstep.c") -> list[Path]:
    """The runtime library's C files for the controller whose ``main`` is in ``main``."""
    ports = ([C_DIR / "orccad_port.c", C_DIR / "orccad_rt_automaton.c"] if main == "orccad_rt.c"
             else [])
    return [C_DIR / "orccad_mt.c", C_DIR / "orccad_dynamics.c", *ports, C_DIR / "orccad_wire.c",
            C_DIR / "orccad_automaton.c", C_DIR / main]


def compiler() -> str:
    """The C compiler's path (``$CC``, else ``cc``, else ``gcc``); raises :class:`BuildError`
    when none is found."""
    names = [os.environ["CC"]] if os.environ.get("CC") else ["cc", "gcc"]
    for name in names:
        found = shutil.which(name)
        if found is not None:
            return found
    raise BuildError(f"orccad sil needs a C compiler: {' or '.join(names)} not found (install "
                     f"gcc, e.g. apt-get install -y gcc, or set CC)")


def extra_flags() -> tuple[str, ...]:
    """The compiler flags added by ``$ORCCAD_SIL_CFLAGS`` (e.g. ``-fsanitize=thread -g`` to run
    the controller under ThreadSanitizer), whitespace-separated."""
    return tuple(os.environ.get("ORCCAD_SIL_CFLAGS", "").split())


def _cache_dir() -> Path:
    root = os.environ.get("ORCCAD_CACHE_DIR")
    return Path(root) if root else Path.home() / ".cache" / "orccad"


def build_executable(sources: list[Path], name: str = "orccad_controller",
                     libraries: tuple[str, ...] = ("-lm",)) -> Path:
    """Compile ``sources`` (with the runtime library's folder and every source's folder on the
    include path: the generated headers sit beside the generated sources) into one
    executable, cached by content (the sources and every header of those folders); return its
    path."""
    cc = compiler()
    flags = (*CFLAGS, *extra_flags())
    folders = list(dict.fromkeys([C_DIR, *(path.parent for path in sources)]))
    digest = hashlib.sha256()
    for part in (cc, *flags, *libraries):
        digest.update(part.encode() + b"\0")
    headers = [header for folder in folders for header in sorted(folder.glob("*.h"))]
    for path in [*sources, *headers]:
        digest.update(path.name.encode() + b"\0" + path.read_bytes() + b"\0")
    target_dir = _cache_dir() / "sil" / digest.hexdigest()[:24]
    target = target_dir / name
    if target.exists():
        return target
    target_dir.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(dir=target_dir) as work:
        partial = Path(work) / name
        includes = [part for folder in folders for part in ("-I", str(folder))]
        command = [cc, *flags, *includes, *map(str, sources), "-o", str(partial), *libraries]
        try:
            done = subprocess.run(command, capture_output=True, text=True,
                                  timeout=_BUILD_TIMEOUT_S)
        except subprocess.TimeoutExpired:
            raise BuildError(f"the C compiler took more than {_BUILD_TIMEOUT_S:g} s") from None
        if done.returncode != 0:
            raise BuildError("the controller does not compile:\n" + done.stderr.strip())
        os.replace(partial, target)  # atomic: a concurrent build finds a whole file or none
    return target
