"""A valued signal that *may* be emitted twice in an instant (issue 34, item 5; HipHop's p13
shape: two parallel branches each emitting ``O`` under its own input) is a run-time error of
the instant whose inputs make both emissions — in ``orccad react``, in ``Reactor.step`` of the
automaton ``orccad codegen`` compiles and in the generated C, with the same located message —
and ``orccad check``, which judges the program and not a run, still refuses it."""

from __future__ import annotations

import subprocess

from orccad_app.cli import main as orccad
from tests.codegen.cbuild import build
from tests.codegen.helpers import agree, make

P13 = """\
mission P13 {
    input A, B, C : int;
    output O : int, Q;
    loop {
        par { if A { emit O(1); } } || { if B { emit O(2); } } || { if C { emit O(?C); } }
        emit Q;
        pause;
    }
}
"""

SCRIPT = "A\nB\nC(7)\nA\nA B C(3)\nA\n"


def test_the_c_raises_the_error_at_the_instant_react_does(tmp_path, capsys):
    (tmp_path / "p13.orc").write_text(P13)
    script = tmp_path / "p13.in"
    script.write_text(SCRIPT)
    made = make(tmp_path / "p13.orc")
    records = agree(made, script)
    assert [r.get("values") for r in records[:4]] == [{"O": 1}, {"O": 2}, {"O": 7}, {"O": 1}]
    error = records[4]["error"]
    assert records[4]["instant"] == 5 and len(records) == 5
    assert error["message"].startswith("run-time error: signal O is emitted twice in one "
                                       "instant (first at ")
    assert (error["line"], error["col"]) == (5, P13.splitlines()[4].index("emit O(2)") + 1)

    assert orccad(["react", str(tmp_path / "p13.orc"), "--inputs", str(script),
                   "--jsonl"]) == 2
    react = capsys.readouterr()
    assert len(react.out.splitlines()) == 4
    done = subprocess.run([str(build(made.program)), str(script)], capture_output=True,
                          text=True, timeout=60)
    assert done.returncode == 2 and done.stdout == react.out
    assert done.stderr == react.err.splitlines()[0] + "\n"


def test_codegen_accepts_it_and_check_still_refuses_it(tmp_path, capsys):
    (tmp_path / "p13.orc").write_text(P13)
    assert orccad(["codegen", str(tmp_path / "p13.orc"), "-o", str(tmp_path / "c")]) == 0
    assert (tmp_path / "c" / "p13.c").exists()
    capsys.readouterr()
    assert orccad(["check", str(tmp_path / "p13.orc")]) == 2
    assert "emitted twice in one instant" in capsys.readouterr().err


def test_a_second_emission_decided_by_data_fails_in_c_as_in_python(tmp_path):
    """The case the compiler always deferred (a data test could rule it out): its C did not
    compile before (the data action that only fails read no memory: an unused parameter)."""
    (tmp_path / "d.orc").write_text(
        "mission D {\n    input A;\n    output O : int;\n    var x := 0;\n"
        "    loop { await A; x := x + 1;\n"
        "        par { if x > 1 { emit O(1); } } || { if x > 2 { emit O(2); } } }\n}\n")
    script = tmp_path / "d.in"
    script.write_text("\nA\nA\nA\nA\n")
    records = agree(make(tmp_path / "d.orc"), script)
    assert [r.get("values") for r in records[:3]] == [{}, {}, {"O": 1}]
    assert records[3]["instant"] == 4 and "emitted twice" in records[3]["error"]["message"]
