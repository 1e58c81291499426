"""Fixtures of the plugin tests: the built-in host and a CLI runner."""

import os
import subprocess
import sys
from pathlib import Path

import pytest

from orccad_app.plugin_host import PluginHost

REPO = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def host():
    """The built-in plugins, loaded through the ``orccad`` entry points."""
    return PluginHost.load(blocked=())


def run_cli(*args, env=None, pythonpath=None):
    """Run ``python -m orccad_app.cli ARGS`` in a subprocess; returns the CompletedProcess.

    Without ``env``, the current environment minus ``ORCCAD_DISABLE_PLUGINS``.
    """
    if env is None:
        env = {k: v for k, v in os.environ.items() if k != "ORCCAD_DISABLE_PLUGINS"}
    environment = dict(env)
    if pythonpath:
        environment["PYTHONPATH"] = os.pathsep.join(
            [str(pythonpath), environment.get("PYTHONPATH", "")]).rstrip(os.pathsep)
    return subprocess.run([sys.executable, "-m", "orccad_app.cli", *args],
                          capture_output=True, text=True, env=environment, cwd=REPO)


def install_dist_info(site, name, version, entry_points):
    """Make ``site`` hold an installed distribution's metadata (what pip writes), so
    ``importlib.metadata`` finds its ``orccad`` entry points when ``site`` is on the path."""
    dist_info = Path(site) / f"{name.replace('-', '_')}-{version}.dist-info"
    dist_info.mkdir(parents=True)
    (dist_info / "METADATA").write_text(
        f"Metadata-Version: 2.1\nName: {name}\nVersion: {version}\n")
    lines = "".join(f"{key} = {value}\n" for key, value in entry_points.items())
    (dist_info / "entry_points.txt").write_text(f"[orccad]\n{lines}")
    return dist_info
