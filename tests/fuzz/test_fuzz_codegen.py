"""Fuzzing ``orccad codegen`` with hostile names and strings (issue 34): the generated missions
of :mod:`tests.fuzz.missions` with their signals, variable and mission renamed from a pool of
names a C header, the compiler or the generator owns (``NAN``, ``errno``, ``linux``,
``status``, ``_Bool``, ``s_NAN`` beside ``NAN``…), a string output carrying text hostile to
C literals and comments (``*/``, ``??/``, quotes, escapes, UTF-8), in a folder whose name is
hostile too (``*/``, ``/*``, a byte that is not UTF-8).

The promises: the command keeps those of docs/limits.md (no traceback, exit 0 or 2 with a
message); and **accepted means it compiles and behaves** — the files it wrote compile under
the strict flags (``-std=c99 -Wall -Wextra -Werror -pedantic``) and the program's records on
the script are ``Reactor.step``'s, run-time errors included. The default run is short (a few
examples: each builds a C program); ``-m fuzz_long`` runs many more.
"""

from __future__ import annotations

import json
import os
import re
import subprocess
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from orccad_app.lang import keywords
from orccad_app.pipeline import compose_mission, load
from tests.codegen.cbuild import STRICT, compiler
from tests.codegen.differential import first_difference, python_records
from tests.fuzz.harness import check_outcome, run_orccad, scratch_folder
from tests.fuzz.missions import missions, scripts

#: the names of the generated missions' interface (tests/fuzz/missions.py) and their kinds
_RENAMED = ("A", "B", "C", "N", "F", "O", "Q", "P", "R", "x")

#: names hostile to C: headers' macros and typedefs, keywords of C (not of the plan
#: language), GNU C's predefined macros, the generated structs' own fields, reserved
#: spellings, a mangled name beside its original, names that differ only in case
_HOSTILE_NAMES = sorted(set("""
    NAN INFINITY HUGE_VAL INT64_MAX INT64_MIN UINT8_MAX SIZE_MAX NULL EOF BUFSIZ errno EDOM
    ERANGE EINVAL stdin stdout stderr FILE size_t int64_t offsetof bool true false int char
    double float long unsigned void static const struct union typedef sizeof goto case switch
    default register volatile restrict inline main linux unix i386 status state m in out
    unused M_PI M_E FP_NAN st_mode S_IFREG EXIT_SUCCESS RAND_MAX isfinite isnan printf
    _Bool __STDC__ _X s_NAN s_int NAN_value s_NAN_value Nan nan nAN t1 e b st r i n0 a0 d0
    ORCCAD_ROLE_NONE orccad_signal_info orccad_error_info ck_add cmp_if ck_finite
    MAIN_DONE M_RUNNING JSON_STATE_COUNT ORCCAD_GENERATED_COMMON ORCCAD_GENERATED_MAIN_H
""".split()) - set(keywords()))

#: mission names: each gives a prefix that must be usable (or the mission is renamed)
_MISSION_NAMES = ["M", "Main", "Int", "Stdint", "Math", "Errno", "_Hidden", "OrccadX",
                  "NAN", "Linux", "A" * 70, "status"]

#: ``--name`` prefixes near the generated and the driver's own identifiers (``json_string``,
#: ``ck_add``, ``MAX_DURATION_NS``, ``phase_table``), or refused (a system header, ``_``)
_PREFIXES = [None, None, "json", "parse", "run", "fail", "status", "max_duration", "ck", "cmp",
             "phase", "a0", "main", "e", "Stdint", "_stdint", "int", "p" * 63]

#: strings hostile to a C string literal or comment (as written in the program, escapes
#: of the plan language included)
_HOSTILE_STRINGS = ["*/", "/*", "/*/", "*/ int x; /*", "??/", "??=", "???", "\\\\", "\\\"",
                    "\\n", "\\t", "é", "\u2028", "%s%n", "\\\\??/", "", "a b"]

#: folder names hostile to the origin comment and the error table (bytes for a non-UTF-8 one)
_FOLDERS = [b"plain", b"x*", b"*/ /*", b"??/", b"non-utf8-\xff\xfe", b"tab\there", b"quote\"d"]

_WORD = re.compile(r"\b(" + "|".join(_RENAMED + ("M",)) + r")\b")


@st.composite
def _renaming(draw) -> dict[str, str]:
    names = draw(st.lists(st.sampled_from(_HOSTILE_NAMES), min_size=len(_RENAMED),
                          max_size=len(_RENAMED), unique=True))
    renaming = dict(zip(_RENAMED, names))
    renaming["M"] = draw(st.sampled_from(_MISSION_NAMES))
    return renaming


@st.composite
def _cases(draw) -> tuple[str, str, bytes, str | None]:
    """(mission, script, folder name, --name): a generated mission renamed, with a string
    output."""
    renaming = draw(_renaming())
    mission = draw(missions())
    string = draw(st.sampled_from(_HOSTILE_STRINGS))
    other = draw(st.sampled_from(_HOSTILE_STRINGS))
    mission = mission.replace("output O, Q;", "output O, Q; output Text : string;")
    mission = mission.replace("  var x := 0;\n", f'  var x := 0;\n  if A {{ emit Text("{string}"); '
                              f'}} else {{ emit Text("{other}"); }}\n', 1)
    text = _WORD.sub(lambda m: renaming[m.group(1)], mission)
    script = _WORD.sub(lambda m: renaming[m.group(1)], draw(scripts()))
    return text, script, draw(st.sampled_from(_FOLDERS)), draw(st.sampled_from(_PREFIXES))


def _build_and_compare(out: Path, source: str, script: Path) -> None:
    """The files ``orccad codegen`` wrote in ``out`` compile under the strict flags, and the
    program agrees with ``Reactor.step`` on ``script``."""
    cc = compiler()
    sources = sorted(str(p) for p in out.glob("*.c"))
    binary = out / "run"
    done = subprocess.run([cc, *STRICT, "-O0", "-o", str(binary), *sources],
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, f"{source}\n{done.stderr[:3000]}"
    run = subprocess.run([str(binary), str(script), "--trace"], capture_output=True,
                         timeout=120)
    assert run.returncode in (0, 1, 2), run.stderr[-2000:]
    got = [json.loads(line) for line in run.stdout.decode("utf-8").splitlines()]
    loaded = load(source)
    composition = compose_mission(loaded, loaded.program.missions[0],
                                  defer_double_emissions=True)
    expected = python_records(composition.automaton, script.read_text(encoding="utf-8"),
                              str(script))
    difference = first_difference(expected, got)
    assert difference is None, f"{difference}\nsource: {source}\nscript:\n" \
                               f"{script.read_text(encoding='utf-8')}"


def _codegen(examples: int):
    @settings(max_examples=examples, deadline=None, database=None,
              suppress_health_check=list(HealthCheck))
    @given(_cases())
    def run(case):
        text, script_text, folder_name, prefix = case
        base = scratch_folder("orccad-fuzz-codegen-")
        folder = os.path.join(os.fsencode(base), folder_name)
        os.makedirs(folder, exist_ok=True)
        source = os.fsdecode(os.path.join(folder, b"m.orc"))
        Path(source).write_text(text, encoding="utf-8")
        script = base / "s.in"
        script.write_text(script_text, encoding="utf-8")
        out = base / "out"
        name = ["--name", prefix] if prefix is not None else []
        outcome = run_orccad(["codegen", source, "--main", "-o", str(out), *name], budget_s=60)
        check_outcome(outcome, budget_s=60)
        if outcome.status == 0:
            _build_and_compare(out, source, script)
    return run


def test_codegen_of_hostile_names_and_strings_compiles_and_agrees():
    _codegen(6)()


@pytest.mark.fuzz_long
def test_long_codegen_of_hostile_names_and_strings():
    _codegen(150)()
