"""Mission sources and helpers shared by the benchmarks (not a test module).

Every benchmark compiles its missions from plan-language text, exactly as ``orccad compile``
does: parse → lower → compile (:func:`compile_source`).
"""

from __future__ import annotations

import os
import platform
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
if str(ROOT) not in sys.path:  # run as ``python bench/x.py`` from the repository root
    sys.path.insert(0, str(ROOT))

from orccad_app.lang.parser import parse  # noqa: E402
from orccad_app.reactive.compiler import compile_program  # noqa: E402
from orccad_app.reactive.lower import lower_mission  # noqa: E402

ABRO = (ROOT / "missions" / "abro.orc").read_text(encoding="utf-8")

#: The inputs of the generated sequential missions.
SEQ_INPUTS = ("A", "B", "C")


def sequential(n: int) -> str:
    """A mission of ``n`` top-level statements, cycling through five kinds.

    ``emit O;`` · ``await A;`` · ``if B { emit O; } else { emit P; }`` · ``await (B or C);``
    · ``emit P;`` — so about 2 in 5 statements wait (one control state each) and every
    reaction tests one or two inputs. The last statement is followed by nothing: the mission
    terminates.
    """
    kinds = (
        "emit O;",
        "await A;",
        "if B { emit O; } else { emit P; }",
        "await (B or C);",
        "emit P;",
    )
    body = "\n".join("    " + kinds[i % len(kinds)] for i in range(n))
    return ("mission Seq {\n    input A, B, C;\n    output O, P;\n" + body + "\n}\n")


def par_of_awaits(n: int) -> str:
    """``par { await A1; } || … || { await AN; }`` then ``emit O``: 2^N control states."""
    inputs = ", ".join(f"A{i}" for i in range(1, n + 1))
    branches = " || ".join(f"{{ await A{i}; }}" for i in range(1, n + 1))
    return (f"mission Par{n} {{\n    input {inputs};\n    output O;\n"
            f"    par {branches}\n    emit O;\n}}\n")


def compile_source(text: str, filename: str = "bench.orc", **options):
    """parse → lower → compile, as the pipeline does (the name check is not needed here)."""
    program = parse(text, filename)
    return compile_program(lower_mission(program, program.missions[0]), **options)


def machine() -> str:
    """One line describing where the figures were measured."""
    return (f"{os.cpu_count()} cores (nproc), {platform.machine()}, "
            f"Python {platform.python_version()} ({platform.python_implementation()}), "
            f"{platform.system()} {platform.release()}")


def percentile(sorted_values: list[float], q: float) -> float:
    """The ``q`` quantile (0…1) of already sorted values, nearest rank."""
    index = min(len(sorted_values) - 1, max(0, round(q * (len(sorted_values) - 1))))
    return sorted_values[index]


#: A Robot-Task of the robot grid (:func:`robot_grid`): a 1 s tracking task with a type-1,
#: a type-2 and a type-3 exception, as ``bench/bench_check.py``'s.
GRID_TASK = """robottask T{r}_{k}() on r{r} {{
    duration 1 s;
    task_function joint_tracking(trajectory = cosine(q0 = [0.5, 0.5, 0.5], omega = pi));
    law pid(kp = 400.0, kv = 40.0);
    module traj : trajectory  period 1 ms wcet 0.1 ms on cpu0 priority 2;
    module ctrl : control_law period 1 ms wcet 0.3 ms on cpu0 priority 1;
    module jl   : joint_limits(margin = 0.05) period 5 ms wcet 0.05 ms on cpu0 priority 3;
    connect traj.qd -> ctrl.qd;
    connect traj.qd_dot -> ctrl.qd_dot;
    connect r{r}.q -> ctrl.q;
    connect r{r}.qdot -> ctrl.qdot;
    connect ctrl.tau -> r{r}.tau;
    connect r{r}.q -> jl.q;
    exception JointLimit from jl : fatal;
    exception TrackingLost from tracking_error(max = 0.2) : abort;
    exception Saturated from torque_saturation : adjust ctrl.kp = 200.0;
}}
"""


def robot_grid(robots: int, tasks: int, *, false_property: bool = False) -> str:
    """A mission of ``robots`` arms in ``par``, each running ``tasks`` Robot-Tasks in
    sequence (each in a ``try … catch``), with two properties: a hand-over and termination
    under fairness; ``false_property`` adds a third that fails (every robot's first task
    never raises TrackingLost)."""
    text = "".join(f"robot r{r} : arm3dof;\n" for r in range(1, robots + 1))
    text += "".join(GRID_TASK.format(r=r, k=k) for r in range(1, robots + 1)
                    for k in range(1, tasks + 1))
    branches = []
    for r in range(1, robots + 1):
        runs = " ".join(f"try {{ run T{r}_{k}(); }} catch TrackingLost {{ emit Lost; }}"
                        for k in range(1, tasks + 1))
        branches.append(runs)
    body = "par { " + " } || { ".join(branches) + " }" if robots > 1 else branches[0]
    second = min(2, tasks)
    text += f"""
mission Grid {{
    output Lost, Done;
    {body}
    emit Done;
}}
property Grid.handover: always (started(T1_{second}) -> once (ended(T1_1) or Lost));
property Grid.terminates: eventually (Done or aborted);
"""
    if false_property:
        text += "property Grid.never_lost: never Lost;\n"
    return text
