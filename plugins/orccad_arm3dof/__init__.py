"""Built-in plugin ``orccad_arm3dof``: the 3-DOF direct-drive arm of RR-1801 §7.1.

The model is ``robots/arm3dof.xml`` at the root of the repository. This package ships it
as ``orccad_arm3dof/arm3dof.xml`` (a symbolic link in the source tree, a copy in a built
wheel), so the plugin, the tests and MuJoCo all read the same file.

In a plan::

    robot arm : arm3dof;       // ports arm.q [rad], arm.qdot [rad/s] (sensors), arm.tau [N·m]
"""

from __future__ import annotations

from pathlib import Path

from orccad_app.plugin_api import RobotType, hookimpl

__all__ = ["MJCF_PATH", "ARM3DOF", "orccad_register_robot_types"]



def _mjcf_path() -> Path:
    """The packaged file, or the repository's when a checkout could not make the symbolic
    link (it is then a small text file holding the link's target)."""
    packaged = Path(__file__).with_name("arm3dof.xml")
    if packaged.read_bytes().lstrip().startswith(b"<"):
        return packaged
    return Path(__file__).resolve().parents[2] / "robots" / "arm3dof.xml"


#: The arm's MJCF file (resolves to ``robots/arm3dof.xml`` in a source checkout).
MJCF_PATH = _mjcf_path()

#: The robot type: 3 joints j1 (waist), j2 (shoulder), j3 (elbow), end effector site.
ARM3DOF = RobotType.from_mjcf(
    "arm3dof", MJCF_PATH,
    summary="3-DOF direct-drive arm of RR-1801 §7.1 (waist, shoulder, elbow)")


@hookimpl
def orccad_register_robot_types(register):
    """The ``arm3dof`` robot type."""
    register(ARM3DOF)
