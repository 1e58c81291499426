"""The TUI with missions that import sub-missions (missions/lib/)."""

from __future__ import annotations

from pathlib import Path

from orccad_app.tui.session import inspect_file, inspect_text, mission_files

RECOVERY = "missions/arm_recovery.orc"


def test_the_browser_lists_missions_not_the_library():
    files = mission_files(["missions"])
    assert RECOVERY in files and not any("/lib/" in f for f in files)
    assert "missions/lib/homing.orc" in mission_files(["missions/lib"])


def test_a_library_file_is_a_file_of_its_own():
    view = inspect_file("missions/lib/homing.orc")
    assert view.ok and view.missions == ["Homing"]


def test_an_edited_text_resolves_its_imports_from_the_file_s_folder():
    text = Path(RECOVERY).read_text(encoding="utf-8")
    assert inspect_text(RECOVERY, text).diagnostics == []
    line = next(n for n, t in enumerate(text.splitlines(), 1) if "lib/homing.orc" in t)
    broken = inspect_text(RECOVERY, text.replace('"lib/homing.orc"', '"lib/nothing.orc"'))
    assert [(d.line, d.severity) for d in broken.diagnostics] == [(line, "error")]
    assert 'cannot import "lib/nothing.orc"' in broken.diagnostics[0].message


def test_an_error_in_an_imported_file_names_that_file(tmp_path):
    (tmp_path / "lib").mkdir()
    (tmp_path / "lib" / "l.orc").write_text("mission L { emit Nope; }\n", encoding="utf-8")
    main = tmp_path / "m.orc"
    main.write_text('from "lib/l.orc" import L;\nmission M { run mission L; }\n',
                    encoding="utf-8")
    [diagnostic] = inspect_file(str(main)).diagnostics
    assert diagnostic.line == 0  # not a line of m.orc
    assert diagnostic.message.startswith(f"{tmp_path / 'lib' / 'l.orc'}:1:18: ")
