"""Traces and the mission run loop import without the terminal UI (Textual)."""

from __future__ import annotations

import subprocess
import sys


def test_trace_and_mission_run_import_without_textual():
    code = ("import sys, orccad_app.trace, orccad_app.mission.run; "
            "print([m for m in sys.modules if m.startswith(('textual', 'orccad_app.tui'))])")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.strip()
    assert out == "[]"


def test_the_trace_package_needs_no_front_end():
    """Only the run's status vocabulary comes from the reactive layer (where it is born:
    ``reactive/status.py``, which imports nothing); no parser, compiler or Robot-Task."""
    code = ("import sys, orccad_app.trace; "
            "print(sorted(m for m in sys.modules if m.startswith(('orccad_app.lang', "
            "'orccad_app.reactive', 'orccad_app.robottask'))))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.strip()
    assert out == "['orccad_app.reactive', 'orccad_app.reactive.status']"
