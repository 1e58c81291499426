"""Writing the generated files: all or nothing, never over files that are not ours.

The output folder may not exist (it is made), or be empty, or hold only regular files with the
names being written (a previous run's: they are replaced). Anything else in it is refused before
anything is written. The files are first written under temporary names in the folder's
parent (a new folder) or in the folder (an existing one) and moved into place only once all
are complete: an interruption leaves the old files or the new ones, never a mixture of
half-written files.
"""

from __future__ import annotations

import os
import shutil
import tempfile
from collections.abc import Callable
from pathlib import Path

from orccad_app.diagnostics import OrccadError

__all__ = ["write_files"]


def write_files(folder: str | Path, files: dict[str, str],
                keep: Callable[[Path], bool] | None = None) -> list[Path]:
    """Write ``files`` (name -> text) into ``folder``; the paths written. ``keep``: the
    entries of an existing folder that are the user's (never written: not in ``files``) and
    stay as they are, where any other file is refused (``orccad codegen --controller``'s
    ``orccad_io.c`` and build outputs)."""
    target = Path(folder)
    if target.exists() and not target.is_dir():
        raise OrccadError(f"{target}: exists and is not a folder (-o names the output folder)")
    if target.is_dir():
        others = sorted(p.name for p in target.iterdir()
                        if (p.name not in files or p.is_symlink() or not p.is_file())
                        and not (keep is not None and p.name not in files and keep(p)))
        if others:
            shown = ", ".join(others[:5]) + (" …" if len(others) > 5 else "")
            raise OrccadError(f"{target}: the output folder holds other files ({shown}); "
                              "choose an empty or new folder")
        return _replace_in(target, files)
    parent = target.parent if str(target.parent) else Path(".")
    if not parent.is_dir():
        raise OrccadError(f"{target}: its parent folder {parent} does not exist")
    try:
        staging = Path(tempfile.mkdtemp(prefix=f".{target.name}.", dir=parent))
    except OSError as error:
        raise OrccadError(f"{target}: cannot write: {error.strerror or error}") from None
    try:
        for name, text in files.items():
            (staging / name).write_text(text, encoding="utf-8")
        os.rename(staging, target)
    except OSError as error:
        raise OrccadError(f"{target}: cannot write: {error.strerror or error}") from None
    finally:
        if staging.exists():
            shutil.rmtree(staging, ignore_errors=True)
    return [target / name for name in files]


def _replace_in(target: Path, files: dict[str, str]) -> list[Path]:
    temporary: dict[str, Path] = {}
    try:
        for name, text in files.items():
            handle, temporary_name = tempfile.mkstemp(prefix=f".{name}.", dir=target)
            with os.fdopen(handle, "w", encoding="utf-8") as stream:
                stream.write(text)
            temporary[name] = Path(temporary_name)
        for name, path in temporary.items():
            os.replace(path, target / name)
    except OSError as error:
        raise OrccadError(f"{target}: cannot write: {error.strerror or error}") from None
    finally:
        for path in temporary.values():
            if path.exists():
                path.unlink()
    return [target / name for name in files]
