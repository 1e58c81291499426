"""ROS 2 at the wire level, without ROS 2 installed (the optional extra ``[ros2]``).

- :mod:`.messages`: ROS 2 messages (CDR, the type hashes of ROS 2 Jazzy) of ``rosbags``;
- :mod:`.bag`: ``orccad run --trace DIR --trace-format rosbag2``, a rosbag2 directory (MCAP
  storage, CDR) with the trace's topics as ROS 2 messages;
- :mod:`.keyexpr` and :mod:`.bridge`: ``--ros2-zenoh``, the plant's joint states and joint
  commands (``topic_based_ros2_control``'s ``/joint_states`` and ``/joint_commands``) and the
  mission's inputs and outputs as ROS 2 topics over Zenoh, in rmw_zenoh's key expressions.

Without the extra, :func:`require` raises an :class:`~orccad_app.diagnostics.OrccadError`
naming what to install (exit status 2).
"""

from __future__ import annotations

import importlib

from orccad_app.diagnostics import OrccadError

__all__ = ["require", "INSTALL_HINT"]

INSTALL_HINT = "pip install -e '.[ros2]' (the rosbags and eclipse-zenoh packages)"


def require(option: str, zenoh: bool = False) -> None:
    """Raise, naming ``option`` and what to install, when the extra is missing."""
    try:
        import rosbags.rosbag2  # noqa: F401 - CDR and rosbag2
        if zenoh:  # the transport
            importlib.import_module("zenoh")
    except ImportError:
        raise OrccadError(f"{option} needs the ros2 extra: {INSTALL_HINT}") from None
