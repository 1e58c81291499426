"""The plant extension a robot type may provide: extra physics, sensor ports, named faults.

A robot type (:class:`~orccad_app.control.robot.RobotType`) whose ``plant_extension()``
returns an instance gets it attached to its plant for each run
(:class:`~orccad_app.executive.plant.MujocoPlant` calls :meth:`PlantExtension.step` before
every integration step and reads its sensor ports like MJCF sensors).
"""

from __future__ import annotations

from typing import Any, Mapping

import numpy as np

__all__ = ["PlantExtension"]


class PlantExtension:
    """Extra physics, sensor ports and faults of a plant (a robot type's plugin provides it).

    Subclasses set :attr:`sensors` (port -> dim) and :attr:`faults` (fault -> description
    with its unit) and override the methods; the defaults do nothing.
    """

    sensors: Mapping[str, int] = {}
    faults: Mapping[str, str] = {}

    def bind(self, model: Any, data: Any) -> None:
        """Called once by the plant before the first step (keep ``model``, the
        ``mujoco.MjModel``, and ``data``, its ``mujoco.MjData``)."""

    def step(self, dt_s: float) -> None:
        """Called before each integration step of ``dt_s`` [s]: set ``data.xfrc_applied`` /
        ``qfrc_applied``, integrate the extension's own states (battery energy...)."""

    def read(self, port: str) -> np.ndarray:
        """The value of the sensor ``port`` now (an array; 0-d for a ``float`` port)."""
        raise KeyError(port)

    def inject(self, fault: str, value: Any) -> None:
        """Apply the fault ``fault`` with ``value`` (a name of :attr:`faults`)."""
        raise KeyError(fault)
