"""Run-time arguments of Robot-Tasks in the executive (issue 11).

``run Dive(depth = d)``, ``run Dive(depth = 2.0 * ?D)``: evaluated in the instant the task
starts, checked then (a refused value ends the run ``failed`` with the argument's location,
the report and the trace kept), shown in the report, the trace and ``react``."""

from __future__ import annotations

import csv
import json
import math
from pathlib import Path

import pytest

from orccad_app.cli import main
from orccad_app.diagnostics import OrccadError
from orccad_app.mission.injection import Injection, parse_injection, typed_injection
from orccad_app.mission.plan import plan_mission
from orccad_app.mission.run import MissionRun
from orccad_app.pipeline import load, select_mission

DIVE = """\
robot auv : auv;
input D : float;
input W : vector;
output Started;
robottask Dive(depth: float = 15.0) on auv {
    module guide : depth_guidance(depth = depth) period 100 ms wcet 1 ms on cpu0 priority 2;
    module pilot : auv_autopilot period 50 ms wcet 1 ms on cpu0 priority 1;
    connect auv.position  -> guide.position;
    connect auv.attitude  -> guide.attitude;
    connect guide.setpoint -> pilot.setpoint;
    connect auv.depth     -> pilot.depth;
    connect auv.attitude  -> pilot.attitude;
    connect auv.velocity  -> pilot.velocity;
    connect pilot.tau     -> auv.tau;
    postcondition measure at_waypoint(tol = 0.5);
}
mission M {
%s
}
"""


def _file(tmp_path: Path, body: str) -> str:
    path = tmp_path / "m.orc"
    path.write_text(DIVE % body, encoding="utf-8")
    return str(path)


class _DepthAtEnd:
    """The vehicle's true depth when each Robot-Task ends [m]."""

    def __init__(self) -> None:
        self.run: MissionRun | None = None
        self.depths: list[float] = []

    def on_task_end(self, t_ns: int, task: str, site: int, outcome: str) -> None:
        self.depths.append(float(self.run.sim.plants["auv"].extension.true_value("depth")))


def _run(path: str, *injections: str, until_s: float = 60.0):
    source = load(path)
    plan = plan_mission(source, select_mission(source, None))
    ends = _DepthAtEnd()
    run = MissionRun(plan, until_ns=int(until_s * 1e9), observers=[ends],
                     injections=[parse_injection(text) for text in injections])
    ends.run = run
    return run.run(), ends.depths


def _orccad(capsys, *argv: str) -> tuple[int, str, str]:
    status = main(list(argv))
    out, err = capsys.readouterr()
    assert "Traceback" not in err
    return status, out, err


def test_a_variable_and_arithmetic_give_the_depth(tmp_path):
    path = _file(tmp_path, "var d := 3.0; var k := 2; run Dive(depth = d * k);")
    result, depths = _run(path)
    assert result.status == "done"
    [record] = result.robot_tasks
    assert (record.name, record.args, record.outcome) == ("Dive", {"depth": 6.0}, "good_end")
    assert depths == [pytest.approx(6.0, abs=0.6)]


def test_a_signal_value_is_read_in_the_instant_the_task_starts(tmp_path):
    path = _file(tmp_path, "loop { await D; run Dive(depth = ?D + 1.0); }")
    result, depths = _run(path, "D(4)@1", "D(7.5)@30", until_s=55.0)
    assert [(r.args, r.start_ns, r.outcome) for r in result.robot_tasks] == [
        ({"depth": 5.0}, 1_000_000_000, "good_end"), ({"depth": 8.5}, 30_000_000_000,
                                                      "good_end")]
    assert depths == [pytest.approx(5.0, abs=0.6), pytest.approx(8.5, abs=0.6)]


def test_an_out_of_range_value_ends_the_run_failed_at_the_argument(tmp_path, capsys):
    path = _file(tmp_path, "await D;\n  emit Started;\n  run Dive(depth = ?D - 10.0);")
    trace = tmp_path / "t.csv"
    status, out, err = _orccad(capsys, "run", path, "--inject", "D(4)@2", "--json",
                               "--trace", str(trace))
    assert status == 1
    report = json.loads(out)
    assert report["status"] == "failed"
    assert report["reason"] == (
        f"{path}:20:12: run-time argument of Dive: depth = -6 is refused when the task "
        "starts: depth_guidance: depth must be >= 0, got -6.0")
    assert report["robot_tasks"] == []
    assert [o["name"] for o in report["outputs"]] == ["Started"]
    rows = list(csv.DictReader(trace.open()))
    reaction = [r for r in rows if r["event"] == "reaction"][-1]
    assert reaction["time_ns"] == "2000000000"
    assert "Dive.arg.depth" in json.loads(reaction["value"])["outputs"]


def test_an_overflow_in_an_argument_is_a_located_failure(tmp_path, capsys):
    path = _file(tmp_path, "await D;\n  run Dive(depth = ?D * 1e300);")
    status, out, _ = _orccad(capsys, "run", path, "--inject", "D(1e10)@1", "--json")
    report = json.loads(out)
    assert status == 1 and report["status"] == "failed"
    assert report["reason"].startswith(f"{path}:19:20: run-time error in ?D * 1e+300: ")
    assert "not a finite number" in report["reason"]


def test_a_non_finite_value_is_refused_when_the_task_starts(tmp_path):
    # --inject and react scripts refuse non-finite values; a value that got through anyway
    # (a plugin raising an input) is refused by the task's start, never used
    path = _file(tmp_path, "await W;\n  run Dive(depth = 1.0);")
    source = load(path)
    plan = plan_mission(source, select_mission(source, None))
    from orccad_app.robottask.binding import ArgumentError, bind_arguments
    from orccad_app.robottask.run_arguments import RunArgument
    from orccad_app.lang import ast
    site = plan.sites[0]
    argument = RunArgument("depth", ast.Name(name="x"), site.site.loc, "Dive.arg.depth")
    with pytest.raises(ArgumentError, match="a finite number is expected, got inf"):
        bind_arguments(site.instance, (argument,), {"Dive.arg.depth": math.inf})
    with pytest.raises(ArgumentError, match="a number is expected, got true"):
        bind_arguments(site.instance, (argument,), {"Dive.arg.depth": True})


def test_the_trace_holds_the_arguments_of_each_start(tmp_path, capsys):
    path = _file(tmp_path, "await D;\n  run Dive(depth = ?D);")
    trace = tmp_path / "t.csv"
    status, out, _ = _orccad(capsys, "run", path, "--inject", "D(3)@1", "--trace", str(trace))
    assert status == 0
    assert "Dive(depth=3)    1.000 →" in out
    rows = [r for r in csv.DictReader(trace.open()) if r["event"] == "task_start"]
    assert [(r["module"], r["job"], json.loads(r["value"])) for r in rows] == [
        ("Dive", "0", {"depth": 3.0})]


def test_the_mcap_trace_types_each_argument(tmp_path, capsys):
    from mcap.reader import make_reader
    path = _file(tmp_path, "await D;\n  run Dive(depth = ?D);")
    trace = tmp_path / "t.mcap"
    assert _orccad(capsys, "run", path, "--inject", "D(3)@1", "--trace", str(trace))[0] == 0
    with trace.open("rb") as handle:
        messages = {c.topic: (s, json.loads(m.data))
                    for s, c, m in make_reader(handle).iter_messages()
                    if c.topic in ("/orccad/task_start", "/mission/args/Dive/depth")}
    schema, start = messages["/orccad/task_start"]
    assert json.loads(schema.data)["properties"]["args_json"] == {"type": "string"}
    assert json.loads(start["args_json"]) == {"depth": 3.0}
    schema, value = messages["/mission/args/Dive/depth"]
    assert json.loads(schema.data)["properties"]["value"] == {"type": "number"}
    assert value == {"value": 3.0}


def test_react_composed_shows_the_arguments(tmp_path, capsys):
    path = _file(tmp_path, "var k := 2.0;\n  await D;\n  run Dive(depth = k * ?D);")
    script = tmp_path / "s.in"
    script.write_text("\nD(1.5)\nDive.at_waypoint\n")
    status, out, _ = _orccad(capsys, "react", path, "--composed", "--inputs", str(script),
                             "--jsonl")
    records = [json.loads(line) for line in out.splitlines()]
    assert status == 0
    assert records[1]["outputs"] == ["Dive.start", "Dive.measure", "Dive.activate",
                                     "Dive.arg.depth"]
    assert records[1]["values"] == {"Dive.arg.depth": 3.0}
    assert records[2]["status"] == "done"


def test_runs_with_run_time_arguments_are_deterministic(tmp_path, capsys):
    path = _file(tmp_path, "loop { await D; run Dive(depth = ?D); }")
    outputs = []
    for name in ("a.csv", "b.csv"):
        status, out, _ = _orccad(capsys, "run", path, "--inject", "D(2)@1", "D(4)@20",
                                 "--until", "40", "--json", "--seed", "3",
                                 "--trace", str(tmp_path / name))
        report = json.loads(out)
        report.pop("wall_time_s")
        outputs.append(report)
    assert outputs[0] == outputs[1]
    assert [t["args"] for t in outputs[0]["robot_tasks"]] == [{"depth": 2.0}, {"depth": 4.0}]
    assert (tmp_path / "a.csv").read_bytes() == (tmp_path / "b.csv").read_bytes()


# ------------------------------------------------------------------ typed injections

@pytest.mark.parametrize("text, value", [
    ("W([10, 0, 15])@1", (10.0, 0.0, 15.0)), ("W([1.5,-2e1, 3])@0", (1.5, -20.0, 3.0)),
    ("D(3)@1", 3.0), ("D(2.5)@1", 2.5),
])
def test_injections_are_typed_against_the_declaration(tmp_path, text, value):
    source = load(_file(tmp_path, "nothing;"))
    declared = {s.name: s for s in source.program.signals}
    injection = parse_injection(text)
    typed = typed_injection(injection, declared[injection.name])
    assert typed.value == value and type(typed.value) is type(value)


@pytest.mark.parametrize("text, message", [
    ("W(3)@1", "--inject W: '3' is not a vector value for W (finite numbers)"),
    ("W@1", "W carries a vector: write W([x, y, ...])@T"),
    ("D([1, 2])@1", "--inject D: '[1, 2]' is not a float value for D (a finite number)"),
    ("D(true)@1", "--inject D: 'true' is not a float value for D"),
    ("Started@1", None),
])
def test_ill_typed_injections_are_refused(tmp_path, capsys, text, message):
    path = _file(tmp_path, "await D; run Dive(depth = ?D);")
    status, _, err = _orccad(capsys, "run", path, "--inject", text)
    assert status == 2
    assert (message or "not an input of mission 'M'") in err


@pytest.mark.parametrize("text", ["W([1, 2)@1", "W(1, 2])@1", "W([1,,2])@1", "W([a])@1"])
def test_malformed_vectors_are_refused_against_the_declaration(tmp_path, text):
    source = load(_file(tmp_path, "nothing;"))
    declared = {s.name: s for s in source.program.signals}
    injection = parse_injection(text)
    with pytest.raises(OrccadError, match="is not a vector value for W"):
        typed_injection(injection, declared["W"])


def test_the_run_types_injections_given_through_the_api(tmp_path):
    source = load(_file(tmp_path, "await D; run Dive(depth = ?D);"))
    plan = plan_mission(source, select_mission(source, None))
    with pytest.raises(OrccadError, match="'\"deep\"' is not a float value for D"):
        MissionRun(plan, injections=[Injection("D", 1, "deep")])
