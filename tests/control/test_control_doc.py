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
