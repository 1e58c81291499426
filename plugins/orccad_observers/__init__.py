"""Built-in plugin ``orccad_observers``: the observer library.

Observers are module kinds with an ``event`` output (see :mod:`orccad_observers.base`):

=====================================  =====================================================
``joint_limits(margin)``               a joint within ``margin`` [rad] of a limit
``tracking_error(max)``                :math:`\\|e\\|_\\infty` above ``max``
``singularity(threshold)``             end-effector manipulability below ``threshold``
``torque_saturation``                  a torque at its (velocity-dependent) bound
``at_rest(tol)``                       every joint speed within ``tol`` [rad/s]
``at_goal(tol)``                       at the reference's final point within ``tol``
``sensor_threshold(sensor, …)``        a sensor ``above`` / ``below`` a value
=====================================  =====================================================
"""

from orccad_app.plugin_api import hookimpl

from orccad_observers.base import Monitor, ObserverInstance, ObserverKind
from orccad_observers.kinematics import Singularity
from orccad_observers.limits import JointLimits, TorqueSaturation
from orccad_observers.motion import AtGoal, AtRest, TrackingError
from orccad_observers.sensor import SensorThreshold

__all__ = [
    "Monitor",
    "ObserverKind",
    "ObserverInstance",
    "JointLimits",
    "TrackingError",
    "Singularity",
    "TorqueSaturation",
    "AtRest",
    "AtGoal",
    "SensorThreshold",
    "OBSERVERS",
    "orccad_register_observers",
]

#: One instance of each observer kind, in the order ``orccad plugins`` lists them.
OBSERVERS = (JointLimits(), TrackingError(), Singularity(), TorqueSaturation(), AtRest(),
             AtGoal(), SensorThreshold())


@hookimpl
def orccad_register_observers(register):
    """The seven observers of the library."""
    for observer in OBSERVERS:
        register(observer)
