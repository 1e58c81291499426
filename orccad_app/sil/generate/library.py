"""The C runtime library (``orccad_app/sil/c``, C99, no allocation, no recursion): where its
files are, which of them a controller compiles, and which ``orccad codegen --module-tasks``
writes beside the generated table.
"""

from __future__ import annotations

from pathlib import Path

__all__ = ["C_DIR", "RUNTIME_FILES", "library_sources"]

C_DIR = Path(__file__).resolve().parent.parent / "c"
"""The runtime library's sources."""

_MODULE_TASK_SOURCES = ("orccad_mt.c", "orccad_mt_trajectory.c", "orccad_mt_laws.c")
"""The Module-Tasks' C: the dispatch (``orccad_mt.c``) and the kinds, one file per family."""
_REALTIME_SOURCES = ("orccad_port.c", "orccad_rt_lifecycle.c", "orccad_rt_record.c",
                     "orccad_rt_deadlock.c", "orccad_rt_automaton.c", "orccad_rt_main.c")
"""The real-time runtime's C besides its threads (``orccad_rt.c``, the ``main`` given)."""


def library_sources(main: str = "orccad_lockstep.c") -> list[Path]:
    """The runtime library's C files for the controller whose ``main`` is in ``main``."""
    runtime = ([C_DIR / name for name in _REALTIME_SOURCES] if main == "orccad_rt.c" else [])
    return [*(C_DIR / name for name in _MODULE_TASK_SOURCES), C_DIR / "orccad_dynamics.c",
            *runtime, C_DIR / "orccad_wire.c", C_DIR / "orccad_automaton.c", C_DIR / main]


RUNTIME_FILES = ("orccad_mt.h", "orccad_mt_kinds.h", "orccad_mt.c", "orccad_mt_trajectory.c",
                 "orccad_mt_laws.c",
                 "orccad_dynamics.h", "orccad_dynamics.c", "orccad_port.h", "orccad_port.c",
                 "orccad_wire.h", "orccad_wire.c", "orccad_automaton.h", "orccad_automaton.c",
                 "orccad_rt.h", "orccad_rt_task.h", "orccad_rt.c", "orccad_rt_lifecycle.c",
                 "orccad_rt_record.c", "orccad_rt_deadlock.c", "orccad_rt_automaton.c",
                 "orccad_adjust.h", "orccad_rt_main.c", "orccad_io.h", "orccad_io_shm.c")
"""The runtime library's files that ``orccad codegen --module-tasks`` writes beside the
table (all generated: the user's ``orccad_io.c`` lives outside the folder)."""
