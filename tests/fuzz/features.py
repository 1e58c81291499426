"""Hypothesis strategies for the plan language's second-round constructs: sub-mission imports
(``from "lib.orc" import M;``), run-time arguments of Robot-Tasks (``run T(kp = ?Gain)``),
computed type-1 updates (``adjust ctrl.kp = min(ctrl.kp * 1.5, kmax)``, ``ramp(a, b, D)``),
sporadic Module-Tasks (``sporadic min_interarrival D``), automaton placement (``automaton on P
reaction D``) and robot sensor parameters (``arm3dof(noise_std = …)``).

:func:`feature_programs` draws a main file and a library file it may import; the values are
drawn around the documented bounds (0, negatives, huge, tiny), so many programs are refused,
which the harness accepts as long as the refusal is a located error with exit status 2.
"""

from __future__ import annotations

from hypothesis import strategies as st

__all__ = ["feature_programs", "LIBRARY"]

_DURATIONS = ["0.5 ms", "1 ms", "2 ms", "50 ms", "1 s", "2 s"]
_BAD_DURATIONS = ["0 s", "0 ms", "1 us", "1e12 s", "400 days"]
_FLOATS = ["1e-4", "0.02", "1.5", "20.0", "800.0"]
_BAD_FLOATS = ["0.0", "-0.0", "1e308", "-5.0", "1e-320"]


def _pick(good: list[str], bad: list[str]) -> st.SearchStrategy[str]:
    """Mostly a good value, sometimes a hostile one (3 to 1)."""
    return st.sampled_from(good * 3 + bad)

#: A library of one sub-mission, importable as ``Settle``.
LIBRARY = """robot arm : arm3dof;
robottask Rest(goal: vector = [1.0, 1.0, 1.0]) on arm {
    duration 0.1 s;
    task_function joint_tracking(trajectory = min_jerk(goal = goal, duration = 0.05));
    law pid(kp = 400.0, kv = 40.0);
}
mission Settle { run Rest(); }
"""


def _expr() -> st.SearchStrategy[str]:
    leaf = st.one_of(st.sampled_from(["ctrl.kp", "kmax", "?Gain"]), _pick(_FLOATS, _BAD_FLOATS))
    return st.recursive(leaf, lambda sub: st.one_of(
        st.builds(lambda a, op, b: f"({a} {op} {b})", sub, st.sampled_from("+-*/"), sub),
        st.builds(lambda f, a, b: f"{f}({a}, {b})", st.sampled_from(["min", "max"]), sub, sub)),
        max_leaves=4)


def _update() -> st.SearchStrategy[str]:
    ramp = st.builds(lambda a, b, d: f"ramp({a}, {b}, {d})", _pick(_FLOATS, _BAD_FLOATS),
                     _pick(_FLOATS, _BAD_FLOATS), _pick(_DURATIONS, _BAD_DURATIONS))
    target = _pick(["ctrl.kp", "ctrl.ki", "ctrl.kv"], ["nope.kp", "ctrl.nope"])
    return st.builds(lambda t, e: f"adjust {t} = {e}", target, st.one_of(_expr(), ramp))


@st.composite
def _task(draw) -> str:
    duration = draw(_pick(_DURATIONS, _BAD_DURATIONS))
    watch = draw(st.sampled_from([f"sporadic min_interarrival {duration}", f"period {duration}"]))
    automaton = draw(st.sampled_from([
        "", "automaton on cpu0;", "automaton on cpu1 reaction 0.05 ms;",
        f"automaton on cpu{draw(st.integers(0, 3))} reaction "
        f"{draw(_pick(_DURATIONS, _BAD_DURATIONS))};"]))
    cpu = draw(st.sampled_from(["cpu0", "cpu1"]))
    return f"""robottask T(kp: float = 100.0, kmax: float = 800.0) on arm {{
    duration 0.2 s;
    task_function joint_tracking(trajectory = cosine(q0 = [0.5, 0.5, 0.5], omega = pi));
    law pid(kp = kp, kv = 20.0, ki = 0.0);
    {automaton}
    module traj : trajectory period 1 ms wcet 0.1 ms on cpu0 priority 2;
    module ctrl : control_law period 1 ms wcet 0.3 ms on cpu0 priority 1;
    connect traj.qd -> ctrl.qd;
    connect traj.qd_dot -> ctrl.qd_dot;
    connect arm.q -> ctrl.q;
    connect arm.qdot -> ctrl.qdot;
    connect ctrl.tau -> arm.tau;
    module err : tracking_error(max = 0.02) {watch} wcet 0.05 ms on {cpu} priority 3;
    connect ctrl.e -> err.e;
    exception Drift from err : {draw(_update())};
    exception Lost from tracking_error(max = 0.2) : abort;
}}
"""


@st.composite
def feature_programs(draw) -> tuple[str, str]:
    """(main file, library file ``lib.orc``): a mission over the new constructs."""
    noise = draw(_pick(["1e-4", "0.0", "0.01"], _BAD_FLOATS))
    robot = draw(_pick(["robot arm : arm3dof;", f"robot arm : arm3dof(noise_std = {noise});",
                        "robot arm : arm3dof(qdot_noise_std = 1e-3, quantization = 1e-4);"],
                       ["robot arm : arm3dof(nope = 1.0);",
                        "robot arm : arm3dof(noise_std = 1e-4, noise_std = 1e-3);"]))
    imported = draw(_pick(["", 'from "lib.orc" import Settle;\n'],
                          ['from "m.orc" import M;\n', 'from "nope.orc" import X;\n',
                           'from "lib.orc" import Rest;\n', 'from "." import X;\n']))
    arg = draw(_pick(["", "kp = ?Gain", "kp = 300.0", "kp = ?Gain, kmax = 400.0"],
                     ["kp = [1.0, 2.0]", "nope = 1.0", "kp = ?Go", "kp = 1e308"]))
    settle = "run mission Settle; " if "Settle" in imported and draw(st.booleans()) else ""
    body = draw(st.sampled_from([
        f"{settle}await Gain; run T({arg});",
        f"{settle}await Gain; abort {{ run T({arg}) within 1 s; }} when Go;",
        f"{settle}run T({arg});"]))
    main = (f"{imported}{robot}\ninput Gain : float; input Go;\n{draw(_task())}"
            f"mission M {{ {body} }}\nproperty M.ends: eventually (done or failed or aborted);\n")
    return main, LIBRARY
