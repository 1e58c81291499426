"""The browser summarizes a mission too large to compile quickly without compiling it: the file
has no error, and its inputs are listed (a run builds only the states it reaches)."""

from __future__ import annotations

from orccad_app.tui.session import SUMMARY_MAX_STATES, inspect_file


def test_a_mission_beyond_the_summary_budget_is_summarized_not_refused(tmp_path):
    inputs = ", ".join(f"A{i}" for i in range(1, 13))
    branches = " || ".join(f"{{ await A{i}; }}" for i in range(1, 13))
    path = tmp_path / "par12.orc"
    path.write_text(f"mission Par12 {{\n input {inputs};\n output O;\n par {branches}\n"
                    " emit O;\n}\n", encoding="utf-8")
    view = inspect_file(str(path))
    assert view.diagnostics == []
    assert f"more than {SUMMARY_MAX_STATES} states" in view.summaries["Par12"]
    assert view.inputs["Par12"] == [f"A{i}" for i in range(1, 13)]
