"""What each run site starts, in the generated C (issue 35 item 5): its Robot-Task and every
parameter as the site gives it (a constant, the default, or computed at start), in the
header, the site table and the phase table's legend; the loop of docs/deploy.md uses it."""

from __future__ import annotations

import re
import subprocess

from orccad_app.cli import main as orccad
from orccad_app.codegen.sites import Given, site_infos
from orccad_app.pipeline import compose_mission, load, select_mission
from tests.codegen.cbuild import STRICT, compiler
from tests.codegen.conftest import MISSIONS, ROOT

TWO_GOALS = """\
robot arm : arm3dof;
input Go;
robottask Reach(goal: vector = [1.0, 1.0, 1.0], kp: float = 400.0) on arm {
    duration 1 s;
    task_function joint_tracking(trajectory = min_jerk(goal = goal, duration = 0.5));
    law pid(kp = kp, kv = 40.0);
    module traj : trajectory  period 1 ms wcet 0.1 ms on cpu0 priority 2;
    module ctrl : control_law period 1 ms wcet 0.3 ms on cpu0 priority 1;
    connect arm.q -> traj.q;
    connect traj.qd -> ctrl.qd;
    connect traj.qd_dot -> ctrl.qd_dot;
    connect arm.q -> ctrl.q;
    connect arm.qdot -> ctrl.qdot;
    connect ctrl.tau -> arm.tau;
}
mission TwoGoals {
    run Reach(goal = [0.2, 0.3, 0.4]);
    await Go;
    run Reach([0.5, 0.6, 0.7], 250.0);
}
"""

PRINT = """\
#include <stdio.h>
#include "P.h"
int main(void)
{
    int site, k, i;
    for (site = 0; site < UP_SITE_COUNT; ++site) {
        const orccad_site_info *s = &P_site_info[site];
        printf("%d %s %d:%d", site, s->task, s->line, s->col);
        for (k = 0; k < s->param_count; ++k) {
            const orccad_site_param *p = &s->params[k];
            printf(" | %s %d %d %d %s", p->name, p->given, p->kind, p->size, p->text);
            for (i = 0; p->value != NULL && i < p->size; ++i) printf(" %.17g", p->value[i]);
            if (p->output >= 0) printf(" -> %s", P_outputs[p->output].name);
        }
        printf("\\n");
    }
    return 0;
}
"""


def _table(tmp_path, path, name: str) -> list[str]:
    cc = compiler()
    out = tmp_path / name
    assert orccad(["codegen", str(path), "-o", str(out)]) == 0
    (out / "print.c").write_text(PRINT.replace("UP_", name.upper() + "_").replace("P_", name + "_")
                                 .replace('"P.h"', f'"{name}.h"'))
    subprocess.run([cc, *STRICT, f"{name}.c", "print.c", "-o", "print"], cwd=out, check=True)
    done = subprocess.run(["./print"], cwd=out, capture_output=True, text=True, check=True)
    return done.stdout.splitlines()


def test_two_sites_of_one_robot_task_say_their_own_constants(tmp_path, capsys):
    source = tmp_path / "two_goals.orc"
    source.write_text(TWO_GOALS)
    lines = _table(tmp_path, source, "two_goals")
    assert lines == [
        "0 Reach 17:5 | goal 1 6 3 [0.2, 0.3, 0.4] 0.20000000000000001 0.29999999999999999 "
        "0.40000000000000002 | kp 0 2 1 400 400",
        "1 Reach 19:5 | goal 1 6 3 [0.5, 0.6, 0.7] 0.5 0.59999999999999998 0.69999999999999996"
        " | kp 1 2 1 250 250"]
    header = (tmp_path / "two_goals" / "two_goals.h").read_text()
    assert "site 0: Reach(goal = [0.2, 0.3, 0.4]) at " in header
    assert "site 1: Reach(goal = [0.5, 0.6, 0.7], kp = 250) at " in header
    assert "       kp: default 400" in header
    source_c = (tmp_path / "two_goals" / "two_goals.c").read_text()
    assert ("sites: 0: Reach(goal = [0.2, 0.3, 0.4]); 1: Reach(goal = [0.5, 0.6, 0.7], "
            "kp = 250) */\nstatic const unsigned char phase_table") in source_c


def test_run_time_arguments_are_computed_at_start_from_their_output(tmp_path):
    lines = _table(tmp_path, MISSIONS / "auv_waypoints.orc", "auv_waypoints")
    assert lines[0].startswith("0 GoTo 72:21 | target 2 6 3 [10, 0, 10] 10 0 10 -> "
                               "GoTo.arg.target")
    assert lines[1].endswith("-> Hold.arg.target")
    assert lines[2] == "2 Surface 82:5"
    source = load(str(MISSIONS / "auv_waypoints.orc"))
    composition = compose_mission(source, select_mission(source, None))
    infos = site_infos(composition.sites)
    assert [p.given for p in infos[0].params] == [Given.AT_START]
    assert infos[0].call_text() == "GoTo(target = <at start>)"


def test_the_site_loop_of_the_docs_runs(tmp_path, monkeypatch):
    cc = compiler()
    loop = re.search(r"```c\n(#include <stdio.h>\n#include <string.h>\n#include "
                     r"\"arm_recovery_c.*?)```", (ROOT / "docs/deploy.md").read_text(),
                     re.S).group(1)
    (tmp_path / "loop.c").write_text(loop)
    monkeypatch.chdir(ROOT)  # the file names as the docs show them
    assert orccad(["codegen", "missions/arm_recovery.orc", "-o",
                   str(tmp_path / "arm_recovery_c")]) == 0
    subprocess.run([cc, *STRICT, "arm_recovery_c/arm_recovery.c", "loop.c", "-o", "loop"],
                   cwd=tmp_path, check=True)
    done = subprocess.run(["./loop"], cwd=tmp_path, capture_output=True, text=True, check=True)
    expected = re.search(r"It prints\n\n```text\n(.*?)```", (ROOT / "docs/deploy.md").read_text(),
                         re.S).group(1)
    assert done.stdout == expected
