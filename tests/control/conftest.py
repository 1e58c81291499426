"""Fixtures of the control-library tests: the arm robot type and a context builder."""

from pathlib import Path

import pytest

from orccad_app.control.spec import module_context
from orccad_app.plugin_host import PluginHost

REPO = Path(__file__).resolve().parents[2]
ARM_XML = REPO / "robots" / "arm3dof.xml"


@pytest.fixture(scope="session")
def host():
    """A plugin host with the built-in plugins, loaded through the entry points."""
    return PluginHost.load(blocked=())


@pytest.fixture(scope="session")
def arm(host):
    """The ``arm3dof`` robot type."""
    return host.robot_types.get("arm3dof")


@pytest.fixture
def cosine_context(host):
    """Context of the RR-1801 §7.1 task: cosine tracking with PID on the arm."""
    def build(law=("pid", {"kp": 400.0, "kv": 40.0, "ki": 10.0}), duration_s=4.0):
        task = ("joint_tracking", {"trajectory": ("cosine", {"q0": [0.5, 0.5, 0.5]})})
        return module_context(host, "arm3dof", task, law, duration_s=duration_s,
                              robot_name="arm")
    return build
