"""Hypothesis scripts through the generated C: valued inputs of every type at their limits,
large clock jumps and run-time errors (overflow, division by zero, non-finite reals), on
``tests/codegen/data/values.orc``; the C agrees with the Python runtime record by record
(values with their types, states, errors with location and message). The same scripts run
on a build with ``-fsanitize=undefined,address``."""

from __future__ import annotations

import itertools
import json
from pathlib import Path

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from orccad_app.codegen.mission import generate_mission
from orccad_app.jsonout import dumps
from orccad_app.pipeline import compose_mission, load
from tests.codegen.cbuild import SANITIZE, STRICT, build, run_lines, run_traces
from tests.codegen.differential import first_difference, python_records

DATA = Path(__file__).parent / "data"
_NAMES = itertools.count()


_MADE: list = []


def _values():
    """The automaton of values.orc and its C (made once; not a fixture: hypothesis would
    print a fixture's whole value with a failing example)."""
    if not _MADE:
        source = load(DATA / "values.orc")
        composition = compose_mission(source, source.program.missions[0])
        _MADE.append((composition.automaton, generate_mission(composition, "values")))
    return _MADE[0]


_INTS = st.one_of(st.integers(-5, 5), st.sampled_from([2**62, 2**63 - 1, -(2**63), -(2**62)]),
                  st.integers(-(2**63), 2**63 - 1))
_FLOATS = st.one_of(st.sampled_from([0.0, -0.0, 0.5, 1e-300, 1e308, -1e308, 3.0, 1e16, 1e15,
                                     2.5e-5, 1.5e-4, 123456789012345.6]),
                    st.floats(allow_nan=False, allow_infinity=False))
_INPUT = st.one_of(
    st.builds(lambda v: f"N({v})", _INTS), st.builds(lambda v: f"D({v})", _INTS),
    st.builds(lambda v: f"X({v!r})", _FLOATS), st.builds(lambda v: f"Y({v!r})", _FLOATS),
    st.builds(lambda v: f"B({'true' if v else 'false'})", st.booleans()),
    st.builds(lambda v: f'S("{v}")', st.sampled_from(["low", "early", "m"])),
    st.builds(lambda v: "V([" + ", ".join(map(repr, v)) + "])",
              st.lists(_FLOATS, min_size=3, max_size=3)),
    st.just("Go"), st.just("Reset"))


@st.composite
def scripts(draw) -> str:
    lines, clock = [], 0
    for _ in range(draw(st.integers(1, 12))):
        jump = draw(st.sampled_from([None, 0, 1, 999, 10**6, 2 * 10**9, 10**12, 10**15]))
        parts = []
        if jump is not None:
            clock = min(clock + jump, 365 * 24 * 3600 * 10**9)
            parts.append(f"@{clock / 1e9!r}")
        parts += draw(st.lists(_INPUT, max_size=4))
        lines.append(" ".join(parts))
    return "\n".join(lines) + "\n"


def _compare(automaton, binary, text: str, folder: Path) -> None:
    path = folder / f"h{next(_NAMES)}.in"
    path.write_text(text)
    expected = python_records(automaton, text, str(path))
    lines, status, stderr = run_lines(binary, path)
    got = [json.loads(line) for line in lines]
    assert first_difference(expected, got) is None, f"{text}\n{first_difference(expected, got)}"
    assert status in (0, 1, 2) and "runtime error" not in stderr, stderr
    # the text itself: what orccad react --jsonl prints (reals in Python's shortest form)
    for line, record in zip(lines, expected):
        if "error" not in record:
            shown = {k: v for k, v in record.items() if k not in ("state", "step_status")}
            assert line.split(', "state": ')[0] + "}" == dumps(shown), line


@settings(max_examples=60, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(text=scripts())
def test_hypothesis_scripts_agree(text, tmp_path_factory):
    automaton, program = _values()
    folder = tmp_path_factory.mktemp("h", numbered=True)
    _compare(automaton, build(program), text, folder)


def test_errors_of_every_kind_agree(tmp_path):
    """One script per run-time error the program can raise, each located and worded as the
    Python runtime words it."""
    automaton, program = _values()
    binary = build(program)
    cases = ["N(9223372036854775807)", "N(3) D(0)", "N(-9223372036854775808) D(-1)",
             "N(-9223372036854775808) D(1)", "X(1e308) Y(1e-300)", "X(1.0) Y(0.0)",
             "X(1e308) N(9223372036854775807)", "V([1e308, 0, 0]) X(10.0)",
             "N(5) D(3)\nN(-7) D(2)\nX(-2.5) Y(-0.0)", "B(true)"]
    for case in cases:
        _compare(automaton, binary, case + "\n", tmp_path)


def test_sanitized_build_runs_the_scripts_clean(tmp_path):
    """Undefined behaviour or a memory error aborts a sanitized program: the checked
    arithmetic and the script reader run clean on hard scripts."""
    automaton, program = _values()
    binary = build(program, STRICT + SANITIZE + ("-O1",))
    texts = ["N(9223372036854775807) D(-1)\nN(-9223372036854775808) D(-1)\n",
             "@0 X(1e308) Y(1e-300) N(-9223372036854775808)\n",
             "@1e-9 V([1e308, -1e308, 5e-324]) X(-1e308) Y(-0.0) B(false) S(\"m\")\n"
             "@31536000 Go N(9223372036854775807) X(2.0)\nGo N(1) X(1e308)\n",
             "S(\"early\") Reset Go N(0) D(0)\n\n\n@2 Go N(1)\n"]
    paths = []
    for number, text in enumerate(texts):
        path = tmp_path / f"s{number}.in"
        path.write_text(text)
        paths.append(path)
    got = run_traces(binary, paths)
    for path in paths:
        expected = python_records(automaton, path.read_text(), str(path))
        assert first_difference(expected, got[str(path)]) is None


def test_reals_print_as_python_prints_them(tmp_path):
    """Python's shortest round-trip form at every decimal exponent (fixed notation from 1e-4 to
    below 1e16, scientific outside), through the C's JSON printer."""
    automaton, program = _values()
    values = [1.2345 * 10.0**k for k in range(-9, 20)] + [
        1e15, 1e16, 9999999999999998.0, 0.0001, 0.00001, 5e-324, 2.0**60, 0.1 + 0.2, -0.0]
    text = "".join(f"X({v!r})\n" for v in values)
    _compare(automaton, build(program), text, tmp_path)
