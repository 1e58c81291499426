"""Issue 34, item 16: docs/editors.md's steps work for a newcomer. The VS Code steps create
the extensions folder they link into; each Neovim and Emacs configuration says which versions
it needs, one serves Debian 12's Neovim 0.7 and eglot 1.9; and where those editors are
installed, each configuration they can run is run headless against `orccad lsp` until the
editor shows the server's diagnostic."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
DOC = (ROOT / "docs" / "editors.md").read_text(encoding="utf-8")
BAD = "mission M {\n    output O;\n    emit P;\n}\n"
MESSAGE = "undeclared signal 'P'"


def _section(title: str) -> str:
    start = DOC.index(f"### {title}\n")
    end = DOC.find("\n### ", start + 1)
    return DOC[start:end if end >= 0 else None]


def _blocks(section: str, language: str) -> list[str]:
    return re.findall(rf"```{language}\n(.*?)```", section, re.S)


def test_the_vs_code_steps_create_the_extensions_folder_before_linking_into_it():
    lines = [line.split("#")[0].strip() for line in _blocks(_section("VS Code"), "console")[0]
             .splitlines()]
    link = next(i for i, line in enumerate(lines) if line.startswith("ln -s"))
    folder = lines[link].split()[-1].rsplit("/", 1)[0]
    assert f"mkdir -p {folder}" in lines[:link], lines


def test_each_editor_configuration_says_which_versions_it_needs():
    neovim = _section("Neovim")
    assert "Neovim 0.10 or later" in neovim and "Neovim 0.7 to 0.9" in neovim
    assert "Debian 12 ships 0.7.2" in neovim
    new, old = _blocks(neovim, "lua")
    assert "vim.lsp.start(" in new
    for api in ("vim.lsp.start(", "vim.fs.", "vim.filetype.add"):  # absent from 0.7
        assert api not in old, api
    emacs = _section("Emacs")
    assert "Emacs 29 or later" in emacs and "eglot 1.9" in emacs and "elpa-eglot" in emacs


@pytest.fixture
def orccad_on_path(tmp_path) -> dict[str, str]:
    """An environment whose ``orccad`` is this interpreter's, and a folder with a bad file."""
    pytest.importorskip("pygls")
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    script = bin_dir / "orccad"
    script.write_text(f'#!/bin/sh\nexec "{sys.executable}" -m orccad_app.cli "$@"\n')
    script.chmod(0o755)
    (tmp_path / "bad.orc").write_text(BAD, encoding="utf-8")
    return {**os.environ, "PATH": f"{bin_dir}{os.pathsep}{os.environ['PATH']}",
            "HOME": str(tmp_path), "XDG_CACHE_HOME": str(tmp_path / "cache"),
            "XDG_STATE_HOME": str(tmp_path / "state")}


def _nvim_version() -> tuple[int, int] | None:
    if shutil.which("nvim") is None:
        return None
    first = subprocess.run(["nvim", "--version"], capture_output=True, text=True).stdout
    found = re.search(r"NVIM v(\d+)\.(\d+)", first)
    return (int(found.group(1)), int(found.group(2))) if found else None


@pytest.mark.skipif(_nvim_version() is None, reason="Neovim is not installed")
def test_the_neovim_configuration_for_the_installed_version_shows_diagnostics(tmp_path,
                                                                              orccad_on_path):
    version = _nvim_version()
    new, old = _blocks(_section("Neovim"), "lua")
    config = tmp_path / "init.lua"
    config.write_text(new if version >= (0, 10) else old, encoding="utf-8")
    probe = ('lua vim.wait(20000, function() return #vim.diagnostic.get(0) > 0 end, 100); '
             'local d = vim.diagnostic.get(0); '
             'io.stdout:write("ft=" .. vim.bo.filetype .. " " .. (d[1] and d[1].message '
             'or "none") .. "\\n")')
    done = subprocess.run(["nvim", "--headless", "-u", str(config), "bad.orc", "-c", probe,
                           "-c", "qa!"], cwd=tmp_path, env=orccad_on_path,
                          capture_output=True, text=True, timeout=60)
    assert f"ft=orccad {MESSAGE}" in done.stdout, (version, done.stdout, done.stderr)


def _eglot_emacs() -> bool:
    if shutil.which("emacs") is None:
        return False
    done = subprocess.run(["emacs", "--batch", "--eval",
                           "(progn (package-initialize) (princ (locate-library \"eglot\")))"],
                          capture_output=True, text=True, timeout=60)
    return done.returncode == 0 and "eglot" in done.stdout


@pytest.mark.skipif(not _eglot_emacs(), reason="Emacs with eglot is not installed")
def test_the_emacs_configuration_shows_diagnostics(tmp_path, orccad_on_path):
    (tmp_path / "init.el").write_text(_blocks(_section("Emacs"), "elisp")[0], encoding="utf-8")
    probe = tmp_path / "probe.el"
    probe.write_text("""\
(package-initialize)                    ; as an interactive start does before init.el
(load (expand-file-name "init.el"))
(find-file "bad.orc")
(run-hooks 'post-command-hook)          ; eglot-ensure connects after the first command
(let ((deadline (+ (float-time) 20)))
  (while (and (< (float-time) deadline) (null (flymake-diagnostics)))
    (accept-process-output nil 0.2)))
(princ (format "mode=%s %S\\n" major-mode
               (mapcar #'flymake-diagnostic-text (flymake-diagnostics))))
(kill-emacs 0)
""", encoding="utf-8")
    done = subprocess.run(["emacs", "--batch", "-l", str(probe)], cwd=tmp_path,
                          env=orccad_on_path, capture_output=True, text=True, timeout=90)
    assert "mode=orccad-mode" in done.stdout and MESSAGE in done.stdout, \
        (done.stdout, done.stderr[-2000:])
