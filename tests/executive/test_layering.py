"""The TCS and the executive stand alone: no language front end, no automata, no Textual."""

from __future__ import annotations

import subprocess
import sys

FORBIDDEN = ("orccad_app.lang", "orccad_app.reactive", "textual")


def test_tcs_and_executive_import_without_the_front_end_or_the_ui():
    code = ("import sys, orccad_app.tcs, orccad_app.executive; "
            f"print([m for m in sys.modules if m.startswith({FORBIDDEN!r})])")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.strip()
    assert out == "[]"
