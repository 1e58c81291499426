"""The complete third-party plugin of docs/plugins.md installs and works.

Its files are extracted from the guide's code blocks marked ``file=PATH``; a ``.dist-info``
with its entry point makes it an installed distribution on ``PYTHONPATH``.
"""

import json
import re
import sys
import tomllib

import numpy as np
import pytest

from orccad_app.control.closed_loop import simulate
from orccad_app.control.module import ModuleContext
from orccad_app.control.spec import module_context, resolve
from orccad_app.plugin_host import PluginHost

from tests.plugins.conftest import REPO, install_dist_info, run_cli

GUIDE = REPO / "docs" / "plugins.md"
BLOCK = re.compile(r"^```\w+ file=(\S+)\n(.*?)^```", re.DOTALL | re.MULTILINE)
CONTRIBUTIONS = {"robot_types": "pendulum", "control_laws": "pd_gravity",
                 "task_functions": "weighted_tracking", "trajectories": "sine",
                 "observers": "speed_limit", "module_kinds": "low_pass"}


def example_files():
    return dict(BLOCK.findall(GUIDE.read_text(encoding="utf-8")))


@pytest.fixture(scope="module")
def installed(tmp_path_factory):
    """The example written to a temporary site directory with its metadata."""
    site = tmp_path_factory.mktemp("site")
    files = example_files()
    for path, text in files.items():
        target = site / path
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_text(text, encoding="utf-8")
    project = tomllib.loads(files["pyproject.toml"])["project"]
    install_dist_info(site, project["name"], project["version"],
                      project["entry-points"]["orccad"])
    return site


@pytest.fixture(scope="module")
def example_host(installed):
    sys.path.insert(0, str(installed))  # the example's dist-info is now on the path
    try:
        yield PluginHost.load(blocked=())
    finally:
        sys.path.remove(str(installed))
        sys.modules.pop("orccad_pendulum", None)


def test_the_guide_contains_the_three_files():
    assert set(example_files()) == {"pyproject.toml", "orccad_pendulum/pendulum.xml",
                                    "orccad_pendulum/__init__.py", "swing.orc"}


def test_orccad_plugins_lists_the_example_with_its_plugin_name(installed):
    result = run_cli("plugins", "--json", pythonpath=installed)
    assert result.returncode == 0, result.stderr
    assert "warning" not in result.stderr
    listing = json.loads(result.stdout)
    assert "orccad_pendulum" in [plugin["name"] for plugin in listing["plugins"]]
    for category, name in CONTRIBUTIONS.items():
        providers = {entry["name"]: entry["plugin"] for entry in listing[category]}
        assert providers.get(name) == "orccad_pendulum", category
    assert {entry["name"] for entry in listing["robot_types"]} >= {"arm3dof", "pendulum"}


def test_the_text_listing_shows_the_example(installed):
    result = run_cli("plugins", pythonpath=installed)
    lines = [line.split() for line in result.stdout.splitlines()]
    for name in CONTRIBUTIONS.values():
        assert [name, "orccad_pendulum"] in [line[:2] for line in lines], name


def test_the_example_tracks_a_sine_on_the_pendulum(example_host):
    assert example_host.failures == []
    robot = example_host.robot_types.get("pendulum")
    task = resolve(example_host, "task function", ("weighted_tracking", {
        "trajectory": ("sine", {"offset": [0.0], "amplitude": [0.5]}), "weights": 2.0}))
    law = resolve(example_host, "control law", ("pd_gravity", {"kp": 80.0, "kv": 8.0}))
    result = simulate(law.build(robot, task.build(robot)), duration_s=2.0)
    assert result.stable and result.rms_error < 0.05


def test_the_example_observer_and_module_kind_run(example_host):
    context = module_context(example_host, "pendulum")
    observer = example_host.module_kind("speed_limit").create({"max": 1.0}, context)
    observer.init()
    assert observer.compute(0.0, {"qdot": [0.5]}) == {"value": 0.5}
    assert observer.compute(0.005, {"qdot": [-1.5]})["event"] is True
    low_pass = example_host.module_kind("low_pass").create({"cutoff": 10.0}, ModuleContext())
    low_pass.init()
    low_pass.compute(0.0, {"u": [0.0]})
    y = low_pass.compute(0.01, {"u": [1.0]})["y"]
    np.testing.assert_allclose(y, 1 - np.exp(-2 * np.pi * 10.0 * 0.01))


def test_the_swing_plan_gets_the_law_default_modules_and_swings(installed):
    """A Robot-Task with a law and no module: pd_gravity's default traj and ctrl drive the
    pendulum (before, only the observer ran and nothing wrote pendulum.tau)."""
    plan = str(installed / "swing.orc")
    tcs = run_cli("tcs", plan, "--task", "Swing", pythonpath=installed)
    assert tcs.returncode == 0, tcs.stderr
    for line in ("traj.qd -> ctrl.qd", "pendulum.q -> ctrl.q", "ctrl.tau -> pendulum.tau",
                 "pendulum.qdot -> speed_limit.qdot"):
        assert line in tcs.stdout, line
    run = run_cli("run", plan, "--json", pythonpath=installed)
    assert run.returncode == 0, run.stderr
    report = json.loads(run.stdout)
    assert report["status"] == "done"
    assert {"Swing.traj", "Swing.ctrl"} <= set(report["modules"])
    assert report["robot_tasks"][0]["tracking_error"]["max"] < 0.1
