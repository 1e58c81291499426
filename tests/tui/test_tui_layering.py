"""The core imports without Textual: only ``orccad_app.tui`` (and ``orccad tui`` when run) does."""

from __future__ import annotations

import subprocess
import sys

CORE = ("orccad_app.lang", "orccad_app.reactive", "orccad_app.robottask", "orccad_app.verify",
        "orccad_app.verify.checker", "orccad_app.executive", "orccad_app.mission.run",
        "orccad_app.trace", "orccad_app.pipeline", "orccad_app.cli",
        "orccad_app.tui.live", "orccad_app.tui.session")


def _loaded(code: str) -> str:
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          check=True).stdout.strip()


def test_the_core_and_the_cli_parser_import_without_textual():
    code = (f"import sys, importlib\nfor m in {CORE!r}: importlib.import_module(m)\n"
            "from orccad_app.cli import build_parser; build_parser()\n"
            "print(sorted(m for m in sys.modules if m.split('.')[0] in ('textual', 'rich')))")
    assert _loaded(code) == "[]"


def test_the_tui_package_is_where_textual_comes_in():
    code = "import sys, orccad_app.tui.app; print('textual' in sys.modules)"
    assert _loaded(code) == "True"


def test_orccad_tui_on_a_missing_file_is_bad_input():
    result = subprocess.run([sys.executable, "-m", "orccad_app.cli", "tui", "nope.orc"],
                            capture_output=True, text=True)
    assert result.returncode == 2 and "nope.orc: no such file" in result.stderr


def test_orccad_tui_speed_must_be_a_factor_or_max():
    result = subprocess.run([sys.executable, "-m", "orccad_app.cli", "tui", "--speed", "0"],
                            capture_output=True, text=True)
    assert result.returncode == 2 and "expected a factor in" in result.stderr
