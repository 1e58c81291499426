"""What a module instance may know about its Robot-Task: :class:`ModuleContext`."""

from __future__ import annotations

from dataclasses import dataclass

from orccad_app.control.errors import ControlError
from orccad_app.control.kinds import Spec
from orccad_app.control.robot import RobotType

__all__ = ["ModuleContext"]


@dataclass(frozen=True)
class ModuleContext:
    """What a module instance may know about its Robot-Task.

    ``robot`` is the robot type the task runs on; ``task_function`` and ``law`` are the
    task's validated :class:`~orccad_app.control.kinds.Spec` s (each module builds its own
    fresh object from them, so modules never share state); ``duration_s`` is the task's
    nominal duration T [s]. Build one by names with
    :func:`orccad_app.control.spec.module_context`.
    """

    robot: RobotType | None = None
    task_function: Spec | None = None
    law: Spec | None = None
    duration_s: float | None = None
    robot_name: str | None = None

    def require_robot(self, who: str) -> RobotType:
        """The robot, or a :class:`ControlError` saying ``who`` needs one."""
        if self.robot is None:
            raise ControlError(f"{who} needs a robot (the Robot-Task's 'on ROBOT')")
        return self.robot
