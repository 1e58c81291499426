"""The time-constrained specification (TCS) of a Robot-Task (RR-1801 §3.2–3.3).

Module-Tasks, ports, connections under the 8 synchronization protocols, the TCS graph and its
coherence checks, schedulability (:func:`analyse_timing`: processors under fixed priority or
EDF, protocol blocking, the bus; :func:`response_time_analysis` for independent tasks), static
deadlock analysis and a placement suggestion. Pure data and analysis: the executive runs it.
"""

from orccad_app.tcs.analysis import ResponseTime, response_time_analysis, utilization
from orccad_app.tcs.bus_delay import BusModel, MessageClass
from orccad_app.tcs.connection import Connection
from orccad_app.tcs.deadlock import DeadlockCycle, check_deadlock_free, find_deadlock_cycles
from orccad_app.tcs.graph import TCS
from orccad_app.tcs.module_task import ModuleTask, PhysicalResource
from orccad_app.tcs.placement import Placement, suggest_placement, traffic_graph
from orccad_app.tcs.port import EVENT, PortDirection, Port
from orccad_app.tcs.phasing import Activation
from orccad_app.tcs.protocol import Protocol, parse_protocol
from orccad_app.tcs.schedulability import Schedulability, TaskTiming, analyse_timing
from orccad_app.tcs.timebase import NS_PER_S, ms, ns, s, to_seconds, us

__all__ = [
    "TCS",
    "ModuleTask",
    "PhysicalResource",
    "Port",
    "PortDirection",
    "EVENT",
    "Connection",
    "Protocol",
    "parse_protocol",
    "utilization",
    "response_time_analysis",
    "ResponseTime",
    "analyse_timing",
    "Schedulability",
    "TaskTiming",
    "BusModel",
    "MessageClass",
    "Activation",
    "find_deadlock_cycles",
    "check_deadlock_free",
    "DeadlockCycle",
    "suggest_placement",
    "traffic_graph",
    "Placement",
    "NS_PER_S",
    "ns",
    "us",
    "ms",
    "s",
    "to_seconds",
]
