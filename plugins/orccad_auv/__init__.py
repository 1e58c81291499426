"""orccad_auv: the autonomous underwater vehicle of RR-1801's second example, as a plugin.

Contributes the robot type ``auv`` (:mod:`orccad_auv.vehicle`, with a plant extension for
buoyancy, battery, leak, sensors and faults: :mod:`orccad_auv.physics`), the guidance task
functions and the autopilot control law as module kinds (:mod:`orccad_auv.control`) and the
observers (:mod:`orccad_auv.observers`). See docs/auv.md.
"""

from __future__ import annotations

from orccad_app.plugin_api import hookimpl

from orccad_auv.control import MODULE_KINDS
from orccad_auv.observers import OBSERVERS
from orccad_auv.physics import AuvPhysics
from orccad_auv.vehicle import AUV, AuvRobotType

__all__ = ["AUV", "AuvRobotType", "AuvPhysics", "MODULE_KINDS", "OBSERVERS"]


@hookimpl
def orccad_register_robot_types(register):
    register(AUV)


@hookimpl
def orccad_register_observers(register):
    for observer in OBSERVERS:
        register(observer)


@hookimpl
def orccad_register_module_kinds(register):
    for kind in MODULE_KINDS:
        register(kind)


@hookimpl
def orccad_plugins_loaded(host):
    if "orccad_observers" not in host.plugins:
        from orccad_app.plugin_api import OrccadError

        raise OrccadError("orccad_auv needs the observer library (plugin orccad_observers)")
