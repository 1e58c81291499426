"""``orccad lsp`` as a command: without the extra it exits 2 naming what to install."""

from __future__ import annotations

import os
import subprocess
import sys

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
