"""The generated interface as a user meets it: the command, what it refuses, the header, the
object's dependencies, and the hand-written loop of docs/deploy.md."""

from __future__ import annotations

import re
import shutil
import subprocess

import pytest

from orccad_app.cli import main as orccad
from tests.codegen.cbuild import STRICT, compiler
from tests.codegen.conftest import MISSIONS, ROOT, generated


def test_codegen_writes_the_files_and_rewrites_its_own(tmp_path, capsys):
    out = tmp_path / "out"
    assert orccad(["codegen", str(MISSIONS / "abro.orc"), "--main", "-o", str(out)]) == 0
    assert sorted(p.name for p in out.iterdir()) == ["abro.c", "abro.h", "abro_main.c"]
    assert orccad(["codegen", str(MISSIONS / "abro.orc"), "--main", "-o", str(out)]) == 0
    assert orccad(["codegen", str(MISSIONS / "abro.orc"), "--name", "Abro2", "-o",
                   str(tmp_path / "b")]) == 0
    assert sorted(p.name for p in (tmp_path / "b").iterdir()) == ["Abro2.c", "Abro2.h"]
    assert "abro_main.c" in capsys.readouterr().out


def test_a_folder_with_other_files_is_refused_untouched(tmp_path, capsys):
    (tmp_path / "notes.txt").write_text("mine")
    assert orccad(["codegen", str(MISSIONS / "abro.orc"), "-o", str(tmp_path)]) == 2
    assert "holds other files (notes.txt)" in capsys.readouterr().err
    assert [p.name for p in tmp_path.iterdir()] == ["notes.txt"]


@pytest.mark.parametrize("name", ["9lives", "a-b", "int", "orccad_x", "x" * 64])
def test_a_bad_prefix_is_refused(name, tmp_path, capsys):
    assert orccad(["codegen", str(MISSIONS / "abro.orc"), "--name", name, "-o",
                   str(tmp_path / "o")]) == 2
    assert "--name" in capsys.readouterr().err
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize("body,message,culprit", [
    ("var x := 0; x := x + 0.5; emit O(x);", "holds a float here and an int", "x + 0.5"),
    ("emit V([1, 2.5]);", "a vector mixing ints and floats", "[1, 2.5]"),
    ('emit T("a"); emit T("b");', "'+' on a string and a string", 'emit T("b")'),
])
def test_what_c_cannot_express_is_refused_located(body, message, culprit, tmp_path, capsys):
    source = tmp_path / "t.orc"
    text = "mission T { output O : int, V : vector, T : string combine +; " + body + " }\n"
    source.write_text(text)
    assert orccad(["codegen", str(source), "-o", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert message in err and f"t.orc:1:{text.index(culprit) + 1}:" in err, err
    assert not (tmp_path / "o").exists()


def test_the_header_documents_types_and_robot_task_roles():
    header = generated("arm_recovery", "ArmRecovery").program.header
    assert "double Gripper_value; /* its value: float */" in header
    assert re.search(r"bool TrackPID_start; /\* TrackPID.start: start Robot-Task TrackPID", header)
    assert "apply the parameter update of TrackPID's type-1 exception Saturated" in header
    assert "set when the observer of TrackPID's 'TrackingLost' fires" in header
    assert "int arm_recovery_phase(const arm_recovery_mem *m, int site);" in header


def test_the_object_needs_no_library(tmp_path):
    cc = compiler()
    if shutil.which("nm") is None:
        pytest.skip("no nm on this machine")
    program = generated("arm_recovery", "ArmRecovery").program
    for name, text in program.files.items():
        (tmp_path / name).write_text(text)
    subprocess.run([cc, *STRICT, "-O2", "-c", "arm_recovery.c"], cwd=tmp_path, check=True)
    undefined = subprocess.run(["nm", "-u", "arm_recovery.o"], cwd=tmp_path, check=True,
                               capture_output=True, text=True).stdout.split()
    assert [s for s in undefined if s not in ("U",)] == []
    text = program.source
    for word in ("malloc", "free(", "setjmp", "static int step"):
        assert word not in text


def test_the_hand_written_loop_of_the_docs_runs(tmp_path):
    cc = compiler()
    loop = re.search(r"```c\n(#include <stdio.h>.*?)```",
                     (ROOT / "docs/deploy.md").read_text(), re.S).group(1)
    (tmp_path / "loop.c").write_text(loop)
    assert orccad(["codegen", str(MISSIONS / "abro.orc"), "-o", str(tmp_path / "abro_c")]) == 0
    subprocess.run([cc, *STRICT, "abro_c/abro.c", "loop.c", "-o", "loop"], cwd=tmp_path,
                   check=True)
    done = subprocess.run(["./loop"], cwd=tmp_path, capture_output=True, text=True, check=True)
    assert done.stdout == "instant 3: O (role 0)\ninstant 6: O (role 0)\n"


def test_an_automaton_over_the_state_budget_is_refused(tmp_path, capsys):
    assert orccad(["codegen", str(MISSIONS / "arm_recovery.orc"), "--max-states", "5", "-o",
                   str(tmp_path / "o"), "--generator", "explicit"]) == 2
    assert "state budget exceeded" in capsys.readouterr().err
    assert not (tmp_path / "o").exists()


def test_past_the_state_budget_auto_writes_the_circuit(tmp_path, capsys):
    assert orccad(["codegen", str(MISSIONS / "arm_recovery.orc"), "--max-states", "5", "-o",
                   str(tmp_path / "o")]) == 0
    header = (tmp_path / "o" / "arm_recovery.h").read_text()
    assert "generator: circuit: the explicit automaton has more than" in header


def test_two_missions_link_and_run_in_one_process(tmp_path):
    """Caller-owned memory and prefixed names: two generated automata (and two instances of
    one) in one program."""
    cc = compiler()
    for stem, mission in (("abro", "ABRO"), ("auv_survey", "AuvSurvey")):
        for name, text in generated(stem, mission).program.files.items():
            (tmp_path / name).write_text(text)
    (tmp_path / "both.c").write_text("""\
#include <stdio.h>
#include "abro.h"
#include "auv_survey.h"
int main(void)
{
    abro_mem a1, a2;
    auv_survey_mem s;
    abro_in in = {0};
    auv_survey_in sin = {0};
    abro_out out;
    auv_survey_out sout;
    abro_reset(&a1); abro_reset(&a2); auv_survey_reset(&s);
    abro_step(&a1, 0, &in, &out); abro_step(&a2, 0, &in, &out);
    in.A = true; in.B = true;
    abro_step(&a1, 1, &in, &out);
    printf("%d", out.O);
    in.A = false; in.B = false;
    abro_step(&a2, 1, &in, &out);
    printf(" %d", out.O);
    auv_survey_step(&s, 0, &sin, &sout);
    printf(" %d\\n", sout.StationKeep_start);
    return 0;
}
""")
    subprocess.run([cc, *STRICT, "abro.c", "auv_survey.c", "both.c", "-o", "both"],
                   cwd=tmp_path, check=True)
    done = subprocess.run(["./both"], cwd=tmp_path, capture_output=True, text=True, check=True)
    assert done.stdout == "1 0 1\n"
