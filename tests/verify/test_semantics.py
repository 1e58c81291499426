"""Translation validation: the temporal meaning of every statement (the ``ltl`` blocks of
docs/language.md, section "Temporal meaning of the statements") is model-checked on the
compiled automata of generated programs.

Each block's first line is a statement template; ``{P}``, ``{Q}`` are generated blocks
instrumented with ``emit BP; … emit EP;`` and ``{W}`` one that takes at least an instant.
Programs are generated from a fixed seed (sequences, ``if``, ``par``, ``await``, ``abort``,
emissions), so a failure is reproducible.
"""

from __future__ import annotations

import random
import re

import pytest

from .conftest import ROOT, formula, holds, model_of

DOC = ROOT / "docs" / "language.md"
SECTION = "## Temporal meaning of the statements"
PROGRAMS_PER_STATEMENT = 4

TASKS = """robot arm : arm3dof;
""" + "".join(f"""
robottask {name}() on arm {{
    duration 1 s;
    task_function joint_tracking(trajectory = cosine(q0 = [0.5, 0.5, 0.5], omega = pi));
    law pid(kp = 400.0, kv = 40.0);
    module traj : trajectory  period 1 ms wcet 0.1 ms on cpu0 priority 2;
    module ctrl : control_law period 1 ms wcet 0.3 ms on cpu0 priority 1;
    module jl   : joint_limits(margin = 0.05) period 5 ms wcet 0.05 ms on cpu0 priority 3;
    connect traj.qd -> ctrl.qd;
    connect traj.qd_dot -> ctrl.qd_dot;
    connect arm.q -> ctrl.q;
    connect arm.qdot -> ctrl.qdot;
    connect ctrl.tau -> arm.tau;
    connect arm.q -> jl.q;
    exception JointLimit from jl : fatal;
    exception TrackingLost from tracking_error(max = 0.2) : abort;
}}
""" for name in ("Arm1", "Arm2"))


def meanings() -> list[tuple[str, list[str]]]:
    text = DOC.read_text(encoding="utf-8").split(SECTION, 1)[1]
    found = []
    for block in re.findall(r"```ltl\n(.*?)```", text, re.S):
        lines = [line.strip() for line in block.strip().splitlines() if line.strip()]
        assert lines[0].startswith("statement: "), lines[0]
        found.append((lines[0][len("statement: "):], lines[1:]))
    return found


def generate(rng: random.Random, depth: int = 2) -> str:
    """A small random block over inputs A1, A2 and outputs O1, O2."""
    simple = ["nothing;", "pause;", "emit O1;", "emit O2;", "await A1;", "await immediate A2;"]
    if depth == 0 or rng.random() < 0.35:
        return rng.choice(simple)
    kind = rng.choice(["seq", "seq", "if", "par", "abort"])
    a, b = generate(rng, depth - 1), generate(rng, depth - 1)
    if kind == "seq":
        return f"{a} {b}"
    if kind == "if":
        return f"if A1 {{ {a} }} else {{ {b} }}"
    if kind == "par":
        return f"par {{ {a} }} || {{ {b} }}"
    return f"abort {{ {a} }} when A2;"


def instantiate(template: str, rng: random.Random) -> str:
    body = template
    for hole in ("P", "Q"):
        body = body.replace(f"{{{hole}}}", f"emit B{hole}; {generate(rng)} emit E{hole};")
    body = body.replace("{W}", f"emit BW; {generate(rng)} pause; emit EW;")
    tasks = TASKS if "run " in body else ""
    return f"""{tasks}
mission M {{
    input I, J, A1, A2;
    output B, E, S, C, H, T, Y, O1, O2, BP, EP, BQ, EQ, BW, EW;
    emit B;
    {body}
}}
"""


CASES = meanings()


def test_every_statement_of_the_reference_has_a_meaning():
    statements = " ".join(t for t, _ in CASES)
    for keyword in ("nothing", "pause", "halt", "emit", "sustain", "await immediate",
                    "await 2", "await 1 s", "await (", "run ", "within", "if I", "if n",
                    "loop {", "each", "repeat", "every", "abort", "when immediate",
                    "weak abort", "suspend", "trap", "try", "par", "race", "signal",
                    "var "):
        assert keyword in statements, keyword


@pytest.mark.parametrize("template,formulas", CASES, ids=[t[:40] for t, _ in CASES])
def test_statement_meaning_holds_on_compiled_automata(template, formulas):
    rng = random.Random(template)
    for _ in range(PROGRAMS_PER_STATEMENT if "{" in template.replace("{ ", "") else 1):
        source = instantiate(template, rng)
        model = model_of(source)
        for text in formulas:
            assert holds(model, text), f"{text}\nfails on\n{source}"


def test_a_wrong_meaning_is_refuted():
    model = model_of(instantiate("await I; emit E;", random.Random(0)))
    assert not holds(model, "always (E <-> (I and (B or previously ((not I) since B))))")
    assert formula("always E") is not None
