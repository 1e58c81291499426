"""``orccad plugins`` lists every contribution with its plugin."""

import json

from orccad_app.cli import main

from tests.plugins.test_host import BUILT_IN


def test_the_listing_names_each_item_and_its_plugin(capsys):
    assert main(["plugins"]) == 0
    out = capsys.readouterr().out
    lines = [line.split() for line in out.splitlines()]
    pairs = {tuple(line[:2]) for line in lines if len(line) >= 2}
    for provided in BUILT_IN.values():
        for name, plugin in provided.items():
            assert (name, plugin) in pairs
    headings = [line for line in out.splitlines() if not line.startswith(" ")]
    assert headings == ["plugins:", "robot types:", "control laws:", "task functions:",
                        "trajectories:", "observers:", "module kinds:"]


def test_json_describes_ports_params_and_timing(capsys):
    assert main(["plugins", "--json"]) == 0
    document = json.loads(capsys.readouterr().out)
    arm = next(r for r in document["robot_types"] if r["name"] == "arm3dof")
    assert arm["plugin"] == "orccad_arm3dof" and arm["dof"] == 3
    assert [(p["name"], p["direction"], p["dim"]) for p in arm["ports"]] == [
        ("q", "out", 3), ("qdot", "out", 3), ("tau", "in", 3)]
    assert arm["torque_limits"][1] == [80.0, 120.0, 60.0]
    control_law = next(e for e in document["module_kinds"] if e["name"] == "control_law")
    assert control_law["default_timing"] == {"period_ns": 1_000_000, "wcet_ns": 500_000,
                                             "bcet_ns": None}
    pid = next(e for e in document["control_laws"] if e["name"] == "pid")
    assert {p["name"]: p["default"] for p in pid["params"]}["kp"] == 400.0
    assert document["failures"] == []


def test_verbose_lists_parameters_and_ports(capsys):
    assert main(["plugins", "-v"]) == 0
    out = capsys.readouterr().out
    assert "param margin: float = 0.1" in out
    assert "port  out event: event" in out
    assert "timing period 5 ms, wcet 0.1 ms" in out


def test_verbose_and_json_say_which_kinds_have_c(capsys):
    """Module kinds and observers: the runtime library's C, a plugin's file, or none (Python
    only, refused by orccad sil)."""
    assert main(["plugins", "--json"]) == 0
    document = json.loads(capsys.readouterr().out)
    c = {e["name"]: e["c"] for e in document["module_kinds"] + document["observers"]}
    assert c["control_law"].startswith("the runtime library (pid")
    assert c["joint_limits"].endswith("observers.c (prefix orccad_obs_joint_limits)")
    assert c["auv_autopilot"].endswith("auv_autopilot.c (prefix orccad_auv_autopilot)")
    assert c["singularity"] is None  # an observer that runs only in Python
    assert main(["plugins", "-v"]) == 0
    out = capsys.readouterr().out.splitlines()
    at = next(k for k, line in enumerate(out) if line.split()[:1] == ["singularity"])
    shown = next(line for line in out[at + 1:] if line.strip().startswith("C "))
    assert "none: Python only" in shown
