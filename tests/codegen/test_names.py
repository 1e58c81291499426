"""Names and text a program puts into the generated C (issue 34, items 1 and 2): signals and
variables named as a header's macros, prefixes that name a system header, text copied into
comments, paths that are not UTF-8. Accepted means it compiles under the strict flags and
agrees with ``Reactor.step``."""

from __future__ import annotations

import json
import os
import re
import subprocess

import pytest

from orccad_app.cli import main as orccad
from orccad_app.codegen.names import (LIBRARY_NAMES, SYSTEM_HEADERS, c_identifier,
                                      default_prefix, own_macros, reserved)
from tests.codegen.cbuild import STRICT, compiler
from tests.codegen.conftest import MISSIONS
from tests.codegen.helpers import agree, make

NAMES = """\
mission Names {
    input NAN, EOF : int, errno, linux, stdin, _Bool, __STDC__, INT64_MAX : float;
    output INFINITY : float, NULL, bool, M_PI : float, st_mode, S_IFREG, status, state,
           EDOM : int, unix, m, in, out, int;
    var offsetof := 0;
    var SIZE_MAX := 1.5;
    loop {
        await NAN or errno;
        offsetof := offsetof + 1;
        emit INFINITY(SIZE_MAX * 2.0);
        emit NULL; emit bool; emit unix; emit m; emit in; emit out; emit int;
        if EOF { emit EDOM(?EOF + offsetof); }
        if INT64_MAX { emit M_PI(?INT64_MAX * 3.0); }
        if linux or stdin { emit st_mode; emit S_IFREG; }
        if _Bool or __STDC__ { emit status; emit state; }
    }
}
"""

SCRIPT = """\

NAN EOF(4) INT64_MAX(0.5)
errno linux _Bool
NAN stdin __STDC__ EOF(-9)
"""

#: every header a generated file includes, and those a controller includes beside them
_HEADERS = ("stdbool.h", "stddef.h", "stdint.h", "math.h", "errno.h", "stdio.h", "stdlib.h",
            "string.h", "sys/stat.h")


def test_signals_and_variables_named_as_macros_compile_and_agree(tmp_path):
    (tmp_path / "names.orc").write_text(NAMES)
    (tmp_path / "names.in").write_text(SCRIPT)
    made = make(tmp_path / "names.orc")
    records = agree(made, tmp_path / "names.in")
    assert records[1]["outputs"] == ["INFINITY", "NULL", "bool", "M_PI", "EDOM", "unix", "m",
                                     "in", "out", "int"]
    assert records[1]["values"] == {"INFINITY": 3.0, "M_PI": 1.5, "EDOM": 5}
    assert "st_mode" in records[2]["outputs"] and "status" in records[2]["outputs"]
    assert records[3]["values"]["EDOM"] == -6
    header = made.program.header
    assert "bool s_NAN; /* NAN */" in header and "bool s_errno; /* errno */" in header
    assert "bool s_int; /* int */" in header and "bool s_status; /* status */" in header
    assert "bool s__Bool; /* _Bool */" in header


@pytest.mark.parametrize("std", ["-std=gnu99", "-std=gnu11"])
def test_the_header_compiles_beside_every_library_header_in_gnu_c(std, tmp_path):
    """GNU C predefines ``linux`` and ``unix``; a controller includes <math.h>, <stdio.h>…
    before the header: no field may be one of their macros."""
    cc = compiler()
    (tmp_path / "names.orc").write_text(NAMES)
    program = make(tmp_path / "names.orc").program
    for name, text in program.files.items():
        (tmp_path / name).write_text(text)
    includes = "".join(f"#include <{h}>\n" for h in _HEADERS)
    (tmp_path / "user.c").write_text(
        "#define _GNU_SOURCE\n" + includes + '#include "names.h"\n'
        "int main(void) { names_mem m; names_in in = {0}; names_out out;\n"
        "  names_reset(&m); names_step(&m, 0, &in, &out);\n"
        "  in.s_NAN = true; in.s_EOF = true; in.s_EOF_value = EOF;\n"
        "  return names_step(&m, 1, &in, &out) == NAMES_RUNNING && out.s_NULL\n"
        "      && out.s_EDOM_value == EOF + 1 ? 0 : 1; }\n")
    subprocess.run([cc, std, "-Wall", "-Wextra", "-Werror", "-o", "user", "user.c",
                    "names.c"], cwd=tmp_path, check=True, capture_output=True)
    assert subprocess.run(["./user"], cwd=tmp_path).returncode == 0


def test_every_macro_of_the_included_headers_is_reserved(tmp_path):
    """The names of :mod:`orccad_app.codegen.names` cover every macro this machine's C library
    and compiler define for the headers, in strict and GNU C: each is given another field
    name."""
    cc = compiler()
    (tmp_path / "h.c").write_text("".join(f"#include <{h}>\n" for h in _HEADERS))
    macros: set[str] = set()
    for flags in (["-std=c99"], ["-std=gnu99", "-D_GNU_SOURCE"], ["-std=gnu11"]):
        done = subprocess.run([cc, *flags, "-dM", "-E", "h.c"], cwd=tmp_path, check=True,
                              capture_output=True, text=True)
        macros |= {re.split(r"[ (]", line)[1] for line in done.stdout.splitlines()
                   if line.startswith("#define ")}
    assert len(macros) > 300
    missed = sorted(name for name in macros if not reserved(name))
    assert missed == [], missed
    taken: set[str] = set()
    assert all(c_identifier(name, taken) != name for name in sorted(macros))


def test_identifiers_keep_their_name_unless_reserved():
    taken: set[str] = set()
    assert [c_identifier(n, taken) for n in ("TrackPID.start", "Gripper", "NAN", "9lives",
                                             "Gripper")] == [
        "TrackPID_start", "Gripper", "s_NAN", "s_9lives", "Gripper_2"]
    assert not reserved("Estop") and reserved("ESTOP") and reserved("errno")
    assert {"NULL", "EOF", "errno", "stdin", "INFINITY", "NAN"} <= LIBRARY_NAMES


def test_robot_task_and_exception_names_that_meet_as_a_macro(tmp_path):
    """A Robot-Task ``INT64`` whose exception is ``MAX``: the composed input ``INT64.MAX`` is
    ``INT64_MAX`` as a C identifier, the <stdint.h> macro."""
    text = (MISSIONS / "arm_pid.orc").read_text()
    (tmp_path / "m.orc").write_text(text.replace("TrackPID", "INT64")
                                    .replace("TrackingLost", "MAX"))
    (tmp_path / "m.in").write_text("\n\n\nINT64.MAX\n\n")
    made = make(tmp_path / "m.orc")
    assert "bool s_INT64_MAX; /* INT64.MAX: set when the observer of INT64's 'MAX' fires */" \
        in made.program.header
    records = agree(made, tmp_path / "m.in")
    assert records[0]["outputs"] == ["INT64.start", "INT64.measure", "INT64.activate"]
    assert (records[3]["outputs"], records[3]["status"], records[3]["reason"]) == (
        ["MAX.raised"], "failed", "MAX")


def test_a_signal_named_as_a_macro_of_the_header_itself(tmp_path):
    """``ABRO_DONE`` is the header's own macro (the mission's status): a field of that name
    was ``bool 1;``."""
    (tmp_path / "abro.orc").write_text(
        "mission ABRO { input ABRO_DONE, ORCCAD_GENERATED_COMMON; output ABRO_STATE_COUNT;\n"
        "  loop { await ABRO_DONE or ORCCAD_GENERATED_COMMON; emit ABRO_STATE_COUNT; } }\n")
    (tmp_path / "abro.in").write_text("\nABRO_DONE\nORCCAD_GENERATED_COMMON\n")
    made = make(tmp_path / "abro.orc")
    records = agree(made, tmp_path / "abro.in")
    assert [r["outputs"] for r in records] == [[], ["ABRO_STATE_COUNT"], ["ABRO_STATE_COUNT"]]
    defined = set(re.findall(r"#define (\w+)", made.program.header))
    assert defined == own_macros("abro")
    assert "bool s_ABRO_DONE; /* ABRO_DONE */" in made.program.header


# ---------------------------------------------------------------- prefixes and file names

@pytest.mark.parametrize("mission, prefix", [
    ("Main", "main"), ("Int", "mission_int"), ("Stdint", "mission_stdint"),
    ("Math", "mission_math"), ("_Private", "private"), ("OrccadRt", "mission_orccad_rt"),
    ("ArmRecovery", "arm_recovery"), ("A" * 80, "a" * 63)])
def test_a_mission_name_gives_a_usable_default_prefix(mission, prefix, tmp_path, capsys):
    source = tmp_path / "m.orc"
    source.write_text(f"mission {mission} {{ input A; output O; await A; emit O; }}\n")
    assert default_prefix(mission) == prefix
    out = tmp_path / "out"
    assert orccad(["codegen", str(source), "--main", "-o", str(out)]) == 0, \
        capsys.readouterr().err
    assert sorted(p.name for p in out.iterdir()) == [f"{prefix}.c", f"{prefix}.h",
                                                     f"{prefix}_main.c"]


def test_main_builds_with_the_folder_on_the_include_path(tmp_path):
    """``Main`` → ``main.h``/``main.c``; ``Stdint`` → ``mission_stdint.h``: a build with
    ``-I`` on the folder finds the system's <stdint.h>, not a generated file."""
    cc = compiler()
    for mission in ("Main", "Stdint"):
        source = tmp_path / f"{mission}.orc"
        source.write_text(f"mission {mission} {{ input A; output O; await A; emit O; }}\n")
        out = tmp_path / mission
        assert orccad(["codegen", str(source), "--main", "-o", str(out)]) == 0
        sources = sorted(str(p) for p in out.glob("*.c"))
        subprocess.run([cc, *STRICT, "-I", str(out), "-o", str(out / "run"), *sources],
                       check=True, capture_output=True)
        (out / "s.in").write_text("\nA\n")
        done = subprocess.run([str(out / "run"), str(out / "s.in")], capture_output=True,
                              text=True, check=True)
        assert '"outputs": ["O"]' in done.stdout.splitlines()[1]


@pytest.mark.parametrize("name, why", [
    ("stdint", "system header"), ("Stdio", "system header"), ("math", "system header"),
    ("_stdint", "beginning with _"), ("int", "C keyword"), ("orccad_x", "orccad_"),
    ("9lives", "not a C identifier"), ("x" * 64, "at most 63")])
def test_a_prefix_naming_a_system_header_or_reserved_is_refused(name, why, tmp_path, capsys):
    assert orccad(["codegen", str(MISSIONS / "abro.orc"), "--name", name, "-o",
                   str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert f"--name '{name}'" in err and why in err, err
    assert not (tmp_path / "o").exists()


def test_the_header_guard_is_the_generators_own(tmp_path):
    """Never a system header's (``_STDINT_H``) nor the runtime library's (``ORCCAD_RT_H``)."""
    (tmp_path / "m.orc").write_text("mission M { input A; output O; await A; emit O; }\n")
    header = make(tmp_path / "m.orc", "rt").program.header
    assert "#ifndef ORCCAD_GENERATED_RT_H\n#define ORCCAD_GENERATED_RT_H\n" in header
    assert SYSTEM_HEADERS >= {"stdint", "stdio", "math", "pthread", "unistd"}


# ---------------------------------------------------------------- text copied into comments

#: (as written in the program, the value) of strings hostile to a C comment or literal
HOSTILE_STRINGS = [("a/*b", "a/*b"), ("c*/d", "c*/d"), ("/*/", "/*/"), ("??/", "??/"),
                   ("??=x", "??=x"), ("tab\\there", "tab\there"), ("new\\nline", "new\nline"),
                   ("back\\\\slash", "back\\slash"), ('say \\"hi\\"', 'say "hi"'),
                   ("\u00e9t\u00e9", "\u00e9t\u00e9")]


def test_strings_with_comment_markers_and_trigraphs_compile_and_agree(tmp_path):
    cases = "\n".join(f'        if ?I == {k} {{ emit S("{written}"); }}'
                      for k, (written, _value) in enumerate(HOSTILE_STRINGS))
    (tmp_path / "s.orc").write_text(
        "mission Strings {\n    input I : int;\n    output S : string;\n"
        f"    loop {{ await I;\n{cases}\n    }}\n}}\n", encoding="utf-8")
    (tmp_path / "s.in").write_text("\n" + "".join(f"I({k})\n"
                                                  for k in range(len(HOSTILE_STRINGS))))
    made = make(tmp_path / "s.orc")
    records = agree(made, tmp_path / "s.in")
    assert [r["values"]["S"] for r in records[1:]] == [value for _, value in HOSTILE_STRINGS]
    assert '"a/ *b" */' in made.program.header and '"c* /d" */' in made.program.header


def test_a_string_holding_nul_is_refused_located(tmp_path, capsys):
    """A C string ends at its first NUL: the string table could not hold it."""
    text = 'mission M { output S : string; emit S("a\\0b"); }\n'
    (tmp_path / "m.orc").write_text(text)
    assert orccad(["codegen", str(tmp_path / "m.orc"), "-o", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    column = text.index('"a') + 1
    assert f"m.orc:1:{column}: error:" in err and "NUL" in err, err
    assert not (tmp_path / "o").exists()


def test_a_path_with_comment_markers_and_bytes_not_utf8(tmp_path):
    """The origin comment of both files escapes ``/*``, ``*/`` and the byte 0xff; the error
    table keeps the path's own bytes, so the C prints the located error as orccad react."""
    cc = compiler()
    folder = os.path.join(os.fsencode(tmp_path), b"x*/ /*y\xff")
    os.makedirs(folder)
    source = os.path.join(folder, b"m.orc")
    text = "mission M { input N : int; output O : int; loop { await N; emit O(10 / ?N); } }\n"
    with open(source, "w") as handle:
        handle.write(text)
    script = tmp_path / "s.in"
    script.write_text("\nN(5)\nN(0)\n")
    out = tmp_path / "out"
    assert orccad(["codegen", os.fsdecode(source), "--main", "-o", str(out)]) == 0
    first = (out / "m.c").read_text(encoding="utf-8").splitlines()[0]
    assert "from " in first and "x* / / *y\\xff/m.orc" in first
    subprocess.run([cc, *STRICT, "-o", str(out / "run"), str(out / "m.c"),
                    str(out / "m_main.c")], check=True, capture_output=True)
    done = subprocess.run([str(out / "run"), str(script)], capture_output=True)
    expected = os.path.join(folder, b"m.orc") + (
        f":1:{text.index('10 /') + 1}: error: run-time error in 10 / ?N: ".encode())
    assert done.returncode == 2 and done.stderr.startswith(expected), done.stderr
    traced = subprocess.run([str(out / "run"), str(script), "--trace"], capture_output=True,
                            text=True)
    error = json.loads(traced.stdout.splitlines()[-1])["error"]
    assert error["file"] == os.fsdecode(source)  # the byte 0xff as Python holds it: \udcff
