"""The timed executive (docs/design.md, RR-1801 §6 SIMPARC): it runs a TCS, nothing more.

A discrete-event kernel runs Module-Task jobs on simulated processors under the 8 port
protocols, with a FIFO bus between processors, dynamic deadlock detection, and a MuJoCo plant
advanced between events. Observers see everything without reaching in. Missions (automata
driving the Module-Tasks) are the mission layer's business (:mod:`orccad_app.mission`).
"""

from orccad_app.executive.bus import Bus, BusStats
from orccad_app.executive.deadlock import DeadlockError
from orccad_app.executive.job import Job, TaskStats
from orccad_app.executive.kernel import EventClass, Kernel, stream_key
from orccad_app.executive.observer import HOOKS, EventLog, Observer
from orccad_app.executive.plant import MujocoPlant, PlantDivergenceError
from orccad_app.executive.processor import Processor, ProcessorStats
from orccad_app.executive.scheduler import EarliestDeadlineFirst, FixedPriority, Scheduler
from orccad_app.executive.simulation import RunStats, Simulation
from orccad_app.executive.task_runtime import ComputeError, ModuleTaskRuntime

__all__ = [
    "Simulation",
    "RunStats",
    "Kernel",
    "EventClass",
    "stream_key",
    "Processor",
    "ProcessorStats",
    "Scheduler",
    "FixedPriority",
    "EarliestDeadlineFirst",
    "Bus",
    "BusStats",
    "MujocoPlant",
    "PlantDivergenceError",
    "Observer",
    "EventLog",
    "HOOKS",
    "Job",
    "TaskStats",
    "DeadlockError",
    "ComputeError",
    "ModuleTaskRuntime",
]
