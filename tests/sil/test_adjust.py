"""The type-1 updates the real-time controller applies itself (``orccad_app/sil/generate/adjust.py``):
which ones, and their computed values in C equal to the mission layer's, bit for bit."""

from __future__ import annotations

import math
import random
import struct
import subprocess

from orccad_app.diagnostics import OrccadError
from orccad_app.lang import ast
from orccad_app.robottask.updates import compute
from orccad_app.sil.generate.adjust import AdjustForm, _NotInC, c_adjustments, c_expression
from orccad_app.sil.generate.automaton import managed_sites
from orccad_app.sil.build.compiler import CFLAGS, compiler
from orccad_app.sil.generate.library import C_DIR
from orccad_app.sil.generate.table import module_table

from tests.sil.helpers import plan_of

PARAMS = {"kp": 100.0, "kv": -2.5, "ki": 0.0, "w": 1e308}
ENV = {"kmax": 800.0, "lo": -3, "tiny": 5e-324}
LEAVES = [0.0, 1.5, 3.0, 0.1, 1e308, 2.0, 7.0]


def _random_expr(rng: random.Random, depth: int) -> ast.Expr:
    if depth == 0 or rng.random() < 0.25:
        pick = rng.random()
        if pick < 0.4:
            return ast.Number(value=rng.choice(LEAVES))
        if pick < 0.6:
            return ast.Name(name=rng.choice(sorted(ENV)))
        return ast.ParamRef(module="ctrl", param=rng.choice(sorted(PARAMS)))
    pick = rng.random()
    sub = [_random_expr(rng, depth - 1) for _ in range(3)]
    if pick < 0.4:
        return ast.Binary(op=rng.choice("+-*/"), left=sub[0], right=sub[1])
    if pick < 0.5:
        return ast.Unary(op="-", operand=sub[0])
    func = rng.choice(["min", "max", "abs", "clip", "min"])
    count = {"abs": 1, "clip": 3}.get(func, rng.choice([2, 3]))
    return ast.Call(func=func, args=tuple(ast.Arg(name=None, value=item) for item in sub[:count]))


def _python(expr: ast.Expr) -> float | None:
    """The mission layer's value, ``None`` where it refuses the computation."""
    try:
        return float(compute(expr, ENV, lambda module, param: PARAMS[param]))
    except OrccadError:
        return None


def test_computed_values_in_c_equal_the_mission_layers_bit_for_bit(tmp_path):
    """300 random update expressions over +, -, *, /, unary -, min, max, abs and clip (NaN,
    infinities, overflow, swapped clip bounds among them), compiled once with the
    controller's helpers (under AddressSanitizer and UndefinedBehaviorSanitizer where the
    compiler has them): each C value has the Python value's bits, and C refuses exactly where
    the mission layer does."""
    rng = random.Random(7)
    offsets = {name: at for at, name in enumerate(PARAMS)}
    cases = []
    for _ in range(300):
        expr = _random_expr(rng, 4)
        code = c_expression(expr, ENV, lambda module, param: f"get({offsets[param]})")
        cases.append((expr, code))
    lines = ["#include <math.h>", "#include <stdio.h>", '#include "orccad_adjust.h"',
             f"static const double p[] = {{{', '.join(v.hex() for v in PARAMS.values())}}};",
             "static double get(int at) { return p[at]; }",
             "static double value(int k, int *ok) {", "    switch (k) {"]
    lines += [f"    case {k}: return {code};" for k, (_, code) in enumerate(cases)]
    lines += ["    default: break;", "    }", "    (void)ok;", "    return 0.0;", "}",
              "int main(void) {", "    int k;", f"    for (k = 0; k < {len(cases)}; k++) {{",
              "        int ok = 1;", "        double v = value(k, &ok);",
              '        printf("%d %a\\n", ok, v);', "    }", "    return 0;", "}", ""]
    source = tmp_path / "values.c"
    source.write_text("\n".join(lines))
    command = [compiler(), *CFLAGS, "-I", str(C_DIR), str(source), "-o",
               str(tmp_path / "values"), "-lm"]
    sanitized = ["-fsanitize=address,undefined", "-fno-sanitize-recover=all", "-g"]
    built = subprocess.run([*command, *sanitized], capture_output=True, text=True, timeout=120)
    if built.returncode != 0 and "-lasan" in built.stderr + built.stdout:  # no sanitizer here
        built = subprocess.run(command, capture_output=True, text=True, timeout=120)
    assert built.returncode == 0, built.stderr
    ran = subprocess.run([str(tmp_path / "values")], capture_output=True, text=True, timeout=60)
    assert ran.returncode == 0 and "runtime error" not in ran.stderr, ran.stderr
    out = ran.stdout.split("\n")
    checked = refused = 0
    for (expr, code), line in zip(cases, out):
        ok, text = line.split()
        expected = _python(expr)
        if expected is None:
            assert ok == "0", code
            refused += 1
            continue
        assert ok == "1", code
        got = float.fromhex(text) if "nan" not in text else math.nan
        if math.isnan(expected):
            assert math.isnan(got), code
        else:
            assert struct.pack("<d", got) == struct.pack("<d", expected), (code, got, expected)
        checked += 1
    assert checked >= 200 and refused >= 10 and checked + refused == len(cases)


def test_a_vector_or_a_string_stays_with_the_supervisor():
    vector = ast.Vector(items=(ast.Number(value=1.0), ast.Number(value=2.0)))
    for expr in (vector, ast.String(value="x"), ast.Name(name="v")):
        try:
            c_expression(expr, {"v": [1.0, 2.0]}, lambda module, param: "0")
        except _NotInC:
            continue
        raise AssertionError(f"{expr} has no C")


def test_the_updates_the_automaton_task_applies():
    """arm_retune's computed kp and ramped ki, arm_recovery's constant kp: the law's gain
    words (broadcast to the three joints); auv_waypoints' site with run-time arguments has
    none (the supervisor binds it)."""
    plan = plan_of("arm_retune.orc")
    table = module_table(plan)
    drift, lagging = c_adjustments(plan, table, managed_sites(plan))
    assert (drift.exception, drift.form, drift.offsets) == ("Drift", AdjustForm.COMPUTED,
                                                            (2, 3, 4))
    assert "adjust_min" in drift.values[0] and "v > 0x0.0p+0" in drift.check  # kp > 0
    assert (lagging.form, lagging.offsets, lagging.duration_ns) == (AdjustForm.RAMP,
                                                                    (8, 9, 10), 1_000_000_000)
    plan = plan_of("arm_recovery.orc")
    (saturated,) = c_adjustments(plan, module_table(plan), managed_sites(plan))
    assert saturated.form is AdjustForm.CONSTANT
    assert saturated.words == ((2, 200.0), (3, 200.0), (4, 200.0))
    plan = plan_of("auv_waypoints.orc")
    assert c_adjustments(plan, module_table(plan), managed_sites(plan)) == ()


def test_a_vector_computed_value_stays_with_the_supervisor(tmp_path):
    """A vector computed value stays with the supervisor; the scalar ones are the task's."""
    from orccad_app.mission.plan import plan_mission
    from orccad_app.pipeline import load, select_mission

    mission = tmp_path / "mixed.orc"
    mission.write_text("""robot arm : arm3dof;

robottask Mixed() on arm {
    duration 2 s;
    task_function joint_tracking(trajectory = cosine(q0 = [0.5, 0.5, 0.5], omega = pi));
    law pid(kp = [100.0, 100.0, 100.0], kv = 20.0);
    module traj : trajectory  period 1 ms wcet 0.1 ms;
    module ctrl : control_law period 1 ms wcet 0.3 ms;
    module err  : tracking_error(max = 0.02) period 5 ms wcet 0.05 ms;
    connect traj.qd     -> ctrl.qd;
    connect traj.qd_dot -> ctrl.qd_dot;
    connect arm.q       -> ctrl.q;
    connect arm.qdot    -> ctrl.qdot;
    connect ctrl.tau    -> arm.tau;
    connect arm.q       -> err.q;
    connect traj.qd     -> err.qd;
    exception Stiff from err : adjust ctrl.kp = min(ctrl.kp * 2.0, [800.0, 700.0, 600.0]);
    exception Drift from tracking_error(max = 0.04) : adjust ctrl.kv = max(ctrl.kv * 1.5, 20.0);
    exception Slow from at_rest(tol = 0.001) : adjust err.max = min(err.max * 2.0, 0.5);
}

mission M { run Mixed(); }
""")
    source = load(str(mission))
    plan = plan_mission(source, select_mission(source, None))
    adjusts = c_adjustments(plan, module_table(plan), managed_sites(plan))
    assert [a.exception for a in adjusts] == ["Drift", "Slow"]


def test_an_update_touching_a_parameter_the_supervisor_updates_stays_with_it():
    """The closure: an update writing or reading a parameter that one of the supervisor's
    updates writes is the supervisor's too, and so on until nothing changes."""
    from types import SimpleNamespace

    from orccad_app.sil.generate.adjust import CAdjust, _Candidate, _closed

    def candidate(name, writes, reads=()):
        adjust = CAdjust(0, name, 0, f"X.{name}.adjust", AdjustForm.COMPUTED, ())
        return _Candidate(adjust, writes, tuple(reads))

    updates = {"A": ("ctrl", "kp"), "B": ("ctrl", "kv"), "C": ("ctrl", "ki"),
               "D": ("err", "max"), "E": ("ctrl", "kp")}
    site = SimpleNamespace(adjustments={name: SimpleNamespace(module=m, param=p)
                                        for name, (m, p) in updates.items()})
    candidates = {"A": candidate("A", ("ctrl", "kp")),            # E (kp) is the supervisor's
                  "B": candidate("B", ("ctrl", "kv"), [("ctrl", "kp")]),  # reads kp
                  "C": candidate("C", ("ctrl", "ki"), [("ctrl", "kv")]),  # reads kv: B's
                  "D": candidate("D", ("err", "max"), [("ctrl", "kd")])}  # kd never changes
    assert sorted(_closed(site, candidates)) == ["D"]
