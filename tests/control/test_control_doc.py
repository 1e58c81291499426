"""docs/control.md: its example runs and its figures are what the command prints."""

import contextlib
import io
import re

from orccad_app.commands.closed_loop import main

from tests.control.conftest import REPO

DOC = (REPO / "docs" / "control.md").read_text(encoding="utf-8")


def blocks(language):
    return re.findall(rf"^```{language}\n(.*?)^```", DOC, re.DOTALL | re.MULTILINE)


def test_the_python_example_prints_what_the_doc_shows():
    [example] = blocks("python")
    lines = example.splitlines()
    last = max(i for i, line in enumerate(lines) if line.startswith("ctrl.compute("))
    lines[last] = f"print({lines[last]})"  # the doc shows the value of the last call
    output = io.StringIO()
    with contextlib.redirect_stdout(output):
        exec(compile("\n".join(lines), "docs/control.md", "exec"), {})
    shown = re.search(r"^# (\{.*\})$", example, re.MULTILINE).group(1)
    assert output.getvalue().strip() == shown


def test_the_closed_loop_figures_are_those_the_command_prints(capsys):
    assert "python -m orccad_app.commands.closed_loop\n" in blocks("sh")
    printed = next(block for block in blocks("text") if block.startswith("arm3dof:"))
    assert main([]) == 0
    assert capsys.readouterr().out == printed


def _cell(table_title: str, row: str, column: int) -> float:
    """A figure of one of the executive tables of the doc (``column`` 1: C = 0)."""
    section = DOC[DOC.index(table_title):]
    line = next(line for line in section.splitlines() if line.startswith(f"| {row} |"))
    return float(line.split("|")[column + 1])


def test_the_executive_figures_are_those_the_bench_prints():
    """docs/control.md's computed-torque figures once were twice what
    ``bench/timing_table.py`` printed (issue 28, 9): one cell of each table is recomputed, and
    the mission as written is its golden run report's figure."""
    import importlib.util
    import json
    import sys

    spec = importlib.util.spec_from_file_location("timing_table",
                                                  REPO / "bench" / "timing_table.py")
    bench = importlib.util.module_from_spec(spec)
    sys.modules["timing_table"] = bench  # its dataclasses look their module up
    try:
        spec.loader.exec_module(bench)
    finally:
        del sys.modules["timing_table"]
    for law, title in (("computed_torque", "Computed torque (`missions/arm_computed_torque"),
                       ("pid", "PID (`missions/arm_pid.orc`), same sweep")):
        printed = float(bench.rms_error(bench.MISSIONS[law], 1.0, 0.0))
        assert abs(_cell(title, "1 ms", 1) - printed) <= 1e-3 * printed, law
    report = json.loads((REPO / "tests/golden/data/run-arm_computed_torque.out").read_text())
    rms = report["robot_tasks"][0]["tracking_error"]["rms"]
    assert f"C = 0.4 ms) gives {rms:.2e} rad" in DOC
