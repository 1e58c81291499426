"""Hostile input (issue 12): every case is a located error with status 2, a correct result or a
documented behaviour — never a traceback, a hang or a silent change. See docs/limits.md."""

from __future__ import annotations

import json
import time
from pathlib import Path

import pytest

from orccad_app.cli import build_parser, main

ROOT = Path(__file__).resolve().parents[1]
ABRO = str(ROOT / "missions" / "abro.orc")
PID = str(ROOT / "missions" / "arm_pid.orc")
RECOVERY = str(ROOT / "missions" / "arm_recovery.orc")


def _reject(constant: str):
    raise ValueError(f"not strict JSON: {constant}")


def strict(text: str):
    """Parse ``text`` as strict JSON (no NaN/Infinity), as JavaScript's JSON.parse does."""
    return json.loads(text, parse_constant=_reject)


def orccad(capsys, *argv: str) -> tuple[int, str, str]:
    status = main(list(argv))
    out, err = capsys.readouterr()
    assert "Traceback" not in err
    return status, out, err


def write(tmp_path: Path, text: str, name: str = "m.orc") -> str:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return str(path)


# ---------------------------------------------------------------- the command line

@pytest.mark.parametrize("argv, message", [
    (["run", PID, "--until", "inf"], "argument --until"),
    (["run", PID, "--until", "1e300"], "argument --until"),
    (["run", PID, "--until", "nan"], "argument --until"),
    (["run", PID, "--until", "0"], "argument --until"),
    (["run", PID, "--realtime", "1e-300"], "argument --realtime"),
    (["run", PID, "--realtime", "nan"], "argument --realtime"),
    (["run", PID, "--seed", "-1"], "argument --seed"),
    (["run", PID, "--bus-us", "1e9"], "argument --bus-us"),
    (["tcs", PID, "--task", "TrackPID", "--processors", "100000"], "argument --processors"),
    (["tcs", PID, "--task", "TrackPID", "--bound", "nan"], "argument --bound"),
    (["compile", ABRO, "--max-states", "0"], "argument --max-states"),
    (["check", ABRO, "--max-states", "1" + "0" * 30], "argument --max-states"),
    (["tui", "--speed", "inf"], "argument --speed"),
    (["campaign", PID, "--spec", "s.toml", "--until", "inf"], "argument --until"),
    (["campaign", PID, "--spec", "s.toml", "--runs", "0"], "argument --runs"),
    (["falsify", PID, "--spec", "s.toml", "-p", "p", "--seed", "-1"], "argument --seed"),
])
def test_out_of_range_numbers_are_usage_errors(capsys, argv, message):
    with pytest.raises(SystemExit) as stop:
        main(argv)
    assert stop.value.code == 2
    err = capsys.readouterr().err
    assert message in err and "Traceback" not in err


@pytest.mark.parametrize("spec, message", [
    ("TrackPID.TrackingLost@1e300", "in [0, 31536000] (one year)"),
    ("TrackPID.TrackingLost@inf", "in [0, 31536000] (one year)"),
    ("TrackPID.TrackingLost@nan", "in [0, 31536000] (one year)"),
    ("TrackPID.TrackingLost(3)@1", "is a pure input: it takes no value"),
])
def test_bad_injections_are_refused(capsys, spec, message):
    status, _, err = orccad(capsys, "run", PID, "--inject", spec, "--until", "0.01")
    assert status == 2 and message in err


@pytest.mark.parametrize("spec, message", [
    ("Gripper@1.6", "Gripper carries a float: write Gripper(value)@T"),
    ("Gripper(nan)@1", "'nan' is not a float value for Gripper (a finite number)"),
    ("Gripper(true)@1", "'true' is not a float value for Gripper"),
    ("Stop(1)@1", "Stop is a pure input"),
])
def test_injected_values_must_fit_their_input(capsys, spec, message):
    status, _, err = orccad(capsys, "run", RECOVERY, "--inject", spec, "--until", "0.01")
    assert status == 2 and message in err


@pytest.mark.parametrize("form", ["repeated", "listed"])
def test_inject_before_the_file_does_not_swallow_it(capsys, form):
    specs = (["--inject", "TrackPID.TrackingLost@0.05", "--inject", "TrackPID.Saturated@0.02"]
             if form == "repeated" else
             ["--inject", "TrackPID.TrackingLost@0.05", "TrackPID.Saturated@0.02"])
    status, out, err = orccad(capsys, "run", *specs, PID, "--json", "--until", "0.1")
    report = strict(out)
    assert status in (0, 1) and report["mission"] == "ArmPID"
    assert {"TrackingLost", "Saturated"} <= {e["name"] for e in report["exceptions"]}


@pytest.mark.parametrize("timing, message", [
    ("TrackPID.ctrl.period_ms=0.0001", "a period must be at least 1 us"),
    ("TrackPID.ctrl.period_ms=1e300", "at most one year"),
    ("TrackPID.ctrl.wcet_ms=nan", "'nan' is not a scalar value (a finite number"),
])
def test_timing_overrides_keep_the_languages_limits(capsys, timing, message):
    status, _, err = orccad(capsys, "run", PID, "--timing", timing, "--until", "0.01")
    assert status == 2 and message in err


def test_inject_at_zero_is_delivered_in_the_first_instant_and_says_so(capsys):
    status, out, err = orccad(capsys, "run", RECOVERY, "--inject", "Stop@0", "--until",
                              "0.01", "--json")
    assert "Stop@0 is present in the mission's first instant" in err
    assert strict(out)["status"] == "timeout"


def test_no_mission_is_the_same_located_error_in_check_and_compile(tmp_path, capsys):
    path = write(tmp_path, "input A;\n")
    for command in ("check", "compile", "react", "run"):
        status, _, err = orccad(capsys, command, path)
        assert status == 2, command
        assert f"{path}:1:1: error: the file declares no mission" in err, command


@pytest.mark.parametrize("command", [["compile", ABRO], ["rta", PID, "--task", "TrackPID"],
                                     ["check", ABRO, "--counterexample"],
                                     ["check", ABRO, "--promela"],
                                     ["tcs", PID, "--task", "TrackPID"]])
def test_output_onto_the_input_file_is_refused(tmp_path, capsys, command):
    source = tmp_path / "copy.orc"
    source.write_text(Path(command[1]).read_text())
    argv = [command[0], str(source), *command[2:]]
    if argv[-1].startswith("--") and argv[-1] != "--task":
        argv.append(str(source))
    else:
        argv += ["-o", str(source)]
    before = source.read_text()
    status, _, err = orccad(capsys, *argv)
    assert status == 2 and "refusing to overwrite the input file" in err
    assert source.read_text() == before


def _subparsers():
    parser = build_parser()
    return parser._subparsers._group_actions[0].choices  # argparse keeps them here


def test_format_flags_have_help_texts():
    for name in ("compile", "rta", "tcs"):
        action = next(a for a in _subparsers()[name]._actions if a.dest == "format")
        assert action.help and "output format" in action.help, name


def test_the_same_flags_across_subcommands():
    commands = _subparsers()

    def options(name: str, dest: str) -> set[str]:
        return {o for a in commands[name]._actions if a.dest == dest for o in a.option_strings}

    for name in ("compile", "check", "react", "run", "tcs", "tui"):
        assert options(name, "mission") == {"--mission", "-m"}, name
    for name in ("compile", "rta", "tcs"):
        assert options(name, "output") == {"-o", "--output"}, name
    for name in ("compile", "check", "react", "rta"):
        assert options(name, "max_states") == {"--max-states"}, name


def test_cli_state_budget_default_is_the_compilers():
    from orccad_app.commands.arguments import DEFAULT_MAX_STATES
    from orccad_app.reactive.compiler import DEFAULT_MAX_STATES as compiler_default

    assert DEFAULT_MAX_STATES == compiler_default


# ---------------------------------------------------------------- numeric limits of the language

@pytest.mark.parametrize("statement, message", [
    ("await 1e400 s;", "longer than one year"),
    ("await 1e5000 s;", "longer than one year"),
    ("await 1e999999 s;", "longer than one year"),
    ("await 366 * 1 s;", None),  # an expression is not a literal: fine
    ("emit N(" + "9" * 5000 + ");", "integer literal out of range"),
    ("emit N(9223372036854775808);", "integer literal out of range"),
    ("emit F(1e400);", "is out of range: not finite"),
    ("emit F(1e-400);", "too small: it would be read as 0"),
])
def test_literals_out_of_range_are_located_errors(tmp_path, capsys, statement, message):
    path = write(tmp_path, "mission M { output N : int, F : float;\n    "
                 + statement + "\n}\n")
    status, _, err = orccad(capsys, "compile", path)
    if message is None:
        return
    assert status == 2 and message in err
    assert f"{path}:2:" in err


def test_largest_integer_literal_is_accepted(tmp_path, capsys):
    path = write(tmp_path, "mission M { output N : int; emit N(9223372036854775807); }\n")
    status, out, _ = orccad(capsys, "compile", path)
    assert status == 0


ROBOTTASK = """robot arm : arm3dof;
robottask T() on arm {{
    duration {duration};
    task_function joint_tracking(trajectory = cosine(q0 = [0.5, 0.5, 0.5], omega = pi));
    law pid(kp = 400.0, kv = 40.0, ki = 10.0);
    module ctrl : control_law period {period} wcet 0.1 ms on cpu0 priority 1;
}}
mission M {{ run T(); }}
"""


@pytest.mark.parametrize("duration, period, message", [
    ("2 s", "0 ms", "a Module-Task period must be at least 1 us, got '0 ms'"),
    ("2 s", "500 ns", "a Module-Task period must be at least 1 us"),
    ("2 s", "1e308 ms", "longer than one year"),
    ("0 s", "1 ms", "a Robot-Task's nominal duration must be at least 1 us, got '0 s'"),
    ("1e400 s", "1 ms", "longer than one year"),
])
def test_periods_and_durations_have_ranges(tmp_path, capsys, duration, period, message):
    path = write(tmp_path, ROBOTTASK.format(duration=duration, period=period))
    status, _, err = orccad(capsys, "compile", path)
    assert status == 2 and message in err, err


def test_integer_division_truncates_like_esterel(tmp_path, capsys):
    path = write(tmp_path, "mission M { output O : int, P : int, F : float;\n"
                           "  emit O(7 / 2); emit P(-7 / 2); emit F(7.0 / 2); }\n")
    status, out, _ = orccad(capsys, "react", path, "--jsonl", "--inputs", write(tmp_path, "\n",
                                                                                 "s.in"))
    assert strict(out.splitlines()[0])["values"] == {"O": 3, "P": -3, "F": 3.5}


def test_integer_overflow_in_react_is_a_located_error(tmp_path, capsys):
    path = write(tmp_path, "mission M { output O : int; var x := 2;\n"
                           "  loop { x := x * x; emit O(x); pause; } }\n")
    script = write(tmp_path, "\n" * 20, "s.in")
    status, out, err = orccad(capsys, "react", path, "--inputs", script)
    assert status == 2
    assert f"{path}:2:15: error: run-time error in x * x: integer overflow" in err
    assert "O(4294967296)" in out


def test_non_finite_arithmetic_is_a_located_error(tmp_path, capsys):
    path = write(tmp_path, "mission M { output F : float; var x := 1e300;\n"
                           "  loop { x := x * x; emit F(x); pause; } }\n")
    status, _, err = orccad(capsys, "react", path, "--inputs", write(tmp_path, "\n\n", "s.in"))
    assert status == 2 and "not a finite number" in err


def test_value_on_a_pure_signal_is_refused(tmp_path, capsys):
    path = write(tmp_path, "mission M { output O; emit O(3); }\n")
    status, _, err = orccad(capsys, "compile", path)
    assert status == 2 and "is pure" in err


@pytest.mark.parametrize("count", ["nan", "(0.0 / 0.0)", "2.5", "-3", "1e300"])
def test_repeat_needs_a_whole_count(tmp_path, capsys, count):
    path = write(tmp_path, f"mission M {{ output O; repeat {count} {{ emit O; pause; }} }}\n")
    script = write(tmp_path, "\n\n", "s.in")
    status, _, err = orccad(capsys, "react", path, "--inputs", script)
    assert status == 2, err


def test_check_abstracts_integers_that_leave_64_bits_fast(tmp_path, capsys):
    path = write(tmp_path, "mission M { output O; var x := 2; loop { x := x * x; "
                           "if x > 5 { emit O; } pause; } }\n")
    start = time.monotonic()
    status, out, _ = orccad(capsys, "check", path)
    assert time.monotonic() - start < 30  # minutes and gigabytes before
    assert status == 0
    assert "data abstracted: 'x' leaves the 64-bit integers" in out


def test_check_names_the_state_bound_when_counters_grow(tmp_path, capsys):
    path = write(tmp_path, "mission M { output O; var x := 2; loop { x := x + 1; "
                           "if x > 5 { emit O; } pause; } }\n")
    status, out, _ = orccad(capsys, "check", path)
    assert status == 0 and "more than 100000 states with exact counters" in out


# ---------------------------------------------------------------- nesting

def _nested(kind: str, depth: int) -> str:
    body = "emit O;"
    for _ in range(depth):
        body = ("par { " + body + " } || { pause; }" if kind == "par"
                else "abort { " + body + " pause; } when A;")
    return "mission M { input A; output O;\n" + body + "\n}\n"


@pytest.mark.parametrize("kind, depth", [("par", 226), ("abort", 140)])
def test_too_deep_nesting_is_refused_where_it_happens(tmp_path, capsys, kind, depth):
    path = write(tmp_path, _nested(kind, depth))
    status, _, err = orccad(capsys, "compile", path)
    assert status == 2 and "blocks nested more than 100 deep" in err
    assert f"{path}:2:" in err and f"{path}:1:1:" not in err


@pytest.mark.parametrize("kind", ["par", "abort"])
@pytest.mark.parametrize("command", ["compile", "check", "react"])
def test_nesting_at_the_limit_runs_every_pass(tmp_path, capsys, kind, command):
    path = write(tmp_path, _nested(kind, 100))
    argv = [command, path] + (["--inputs", write(tmp_path, "A\n", "s.in")]
                              if command == "react" else [])
    status, _, err = orccad(capsys, *argv)
    assert status == 0, err


@pytest.mark.parametrize("command", ["compile", "check", "react"])
def test_a_flat_1000_term_sum_is_not_too_deep(tmp_path, capsys, command):
    path = write(tmp_path, "mission M { output O : int; emit O(" + " + ".join(["1"] * 1000)
                 + "); }\n")
    argv = [command, path] + (["--inputs", write(tmp_path, "\n", "s.in"), "--jsonl"]
                              if command == "react" else [])
    status, out, err = orccad(capsys, *argv)
    assert status == 0, err
    if command == "react":
        assert strict(out)["values"] == {"O": 1000}


# ---------------------------------------------------------------- diagnostics

def test_tabs_keep_the_caret_under_the_error(tmp_path, capsys):
    path = write(tmp_path, "mission M {\n\toutput O;\n\tawait\tC;\n}\n")
    status, _, err = orccad(capsys, "compile", path)
    shown, caret = err.splitlines()[1:3]
    assert status == 2 and f"{path}:3:8:" in err
    assert shown[caret.index("^")] == "C"


@pytest.mark.parametrize("separator", ["\f", "\u2028", "\v", "\x85"])
def test_odd_line_separators_do_not_shift_the_line_shown(tmp_path, capsys, separator):
    path = write(tmp_path, f"mission M {{\n  output O;{separator} emit O;\n  await C;\n}}\n")
    status, _, err = orccad(capsys, "compile", path)
    head, shown, caret = err.splitlines()[:3]
    assert status == 2
    if f"{path}:3:9: error: undeclared signal 'C'" in head:  # a separator the parser skips
        assert "await C;" in shown and shown[caret.index("^")] == "C"
    else:  # a character the parser refuses, shown on its own line
        assert f"{path}:2:12: error: unexpected character" in head
        assert "output O;" in shown and caret.index("^") == shown.index("O;") + 2


def test_a_byte_order_mark_is_accepted(tmp_path, capsys):
    path = tmp_path / "bom.orc"
    path.write_bytes(b"\xef\xbb\xbfmission M { output O; emit O; }\n")
    status, out, _ = orccad(capsys, "compile", str(path))
    assert status == 0 and "outputs: O" in out


def test_a_byte_order_mark_keeps_columns_right(tmp_path, capsys):
    path = tmp_path / "bom.orc"
    path.write_bytes(b"\xef\xbb\xbfmission M { await C; }\n")
    status, _, err = orccad(capsys, "compile", str(path))
    shown, caret = err.splitlines()[1:3]
    assert status == 2 and shown[caret.index("^")] == "C"


# ---------------------------------------------------------------- react scripts

VALUED = ("mission M { input Battery : float, Name : string, N : int, A; "
          "output O : int, Q : string;\n"
          "  loop { await (Battery or Name or N or A); if Name { emit Q(?Name); } "
          "if N { emit O(?N); } } }\n")


@pytest.mark.parametrize("line, message", [
    ("@nan", "time @nan is out of range"),
    ("@inf", "time @inf is out of range"),
    ("@1e300 A", "time @1e300 is out of range"),
    ("@-1", "is negative"),
    ("Battery(nan)", "'nan' is not a float value for Battery (a finite number)"),
    ("Battery(inf)", "is not a float value"),
    ("Battery(1e400)", "is not a float value"),
    ("N(99999999999999999999)", "is not a int value for N"),
    ("N(" + "9" * 5000 + ")", "is not a int value for N"),
    ("A(3)", "A is a pure signal: it takes no value"),
])
def test_bad_script_values_are_located_errors(tmp_path, capsys, line, message):
    script = write(tmp_path, "A\n" + line + "\n", "s.in")
    status, _, err = orccad(capsys, "react", write(tmp_path, VALUED), "--inputs", script)
    assert status == 2 and f"{script}:2:" in err and message in err


def test_a_hash_inside_a_string_is_not_a_comment(tmp_path, capsys):
    script = write(tmp_path, 'A\n@0 Name("a#b") # a comment\nName("x)y")\n', "s.in")
    status, out, err = orccad(capsys, "react", write(tmp_path, VALUED), "--inputs", script,
                              "--jsonl")
    assert status == 0, err
    assert [strict(line)["values"] for line in out.splitlines()] == [{}, {"Q": "a#b"},
                                                                    {"Q": "x)y"}]


def test_react_columns_stay_aligned_after_times(tmp_path, capsys):
    script = write(tmp_path, "@0 A\n@10.25 Battery(1.5)\nA\n@100 Name(\"a long name\")\n",
                   "s.in")
    status, out, _ = orccad(capsys, "react", write(tmp_path, VALUED), "--inputs", script)
    lines = out.splitlines()
    assert status == 0 and len(lines) == 4
    assert len({line.index("->") for line in lines}) == 1
    assert len({line.index("[") for line in lines}) == 1


# ---------------------------------------------------------------- strict JSON

def test_plugins_json_is_strict(capsys):
    status, out, _ = orccad(capsys, "plugins", "--json")
    document = strict(out)
    assert status == 0 and "-Infinity" not in out
    arm = next(r for r in document["robot_types"] if r["name"] == "arm3dof")
    assert arm["torque_limits"]


def test_react_jsonl_is_strict_with_extreme_values(tmp_path, capsys):
    script = write(tmp_path, "@0 Battery(1e308)\nN(-9223372036854775808)\n", "s.in")
    status, out, _ = orccad(capsys, "react", write(tmp_path, VALUED), "--inputs", script,
                            "--jsonl")
    records = [strict(line) for line in out.splitlines()]
    assert status == 0 and records[1]["values"] == {"O": -9223372036854775808}


def test_run_json_is_strict(capsys):
    status, out, _ = orccad(capsys, "run", PID, "--json", "--until", "0.05")
    assert strict(out)["mission"] == "ArmPID"


def test_tcs_json_is_strict(capsys):
    status, out, _ = orccad(capsys, "tcs", PID, "--task", "TrackPID", "--format", "json")
    assert status in (0, 1) and strict(out)


def test_non_finite_values_are_null_in_json():
    from orccad_app.jsonout import dumps

    text = dumps({"a": float("nan"), "b": [float("inf"), -float("inf")], "c": 1.5})
    assert strict(text) == {"a": None, "b": [None, None], "c": 1.5}


def test_a_very_long_line_is_shown_as_a_window_around_the_error(tmp_path, capsys):
    path = write(tmp_path, "mission M { output O; " + "emit O; pause; " * 5000 + "await C; }\n")
    status, _, err = orccad(capsys, "compile", path)
    head, shown, caret = err.splitlines()[:3]
    assert status == 2 and "undeclared signal 'C'" in head
    assert len(shown) < 200 and shown[caret.index("^")] == "C"


def test_trace_values_are_strict_json():
    import numpy as np

    from orccad_app.trace.recorder import to_json

    assert strict(to_json([1.0, float("nan"), np.array([np.inf, 2.0])])) == [1.0, None,
                                                                           [None, 2.0]]
