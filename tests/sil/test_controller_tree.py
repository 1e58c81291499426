"""The controller as a C tree built without ORCCAD (issue 35 items 2-3): ``orccad codegen
--controller`` writes it with its Makefile; ``make`` builds it with no Python on ``PATH``;
``orccad sil --controller`` runs the prebuilt controller against the plant and the run ends as
``orccad run``'s; the same for an aarch64 build under qemu-user (skipped with the reason where
the cross tools are missing); the main alone on the robot; the generation gap."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from orccad_app.mission.plan import plan_mission
from orccad_app.pipeline import load, select_mission
from orccad_app.sil.generate.automaton import mission_automaton
from orccad_app.sil.generate.tree import controller_tree

ROOT = Path(__file__).resolve().parents[2]
RECOVERY = ["missions/arm_recovery.orc", "--inject", "TrackPID.TrackingLost@2.5"]
QEMU = ("qemu-aarch64", "-L", "/usr/aarch64-linux-gnu")

STUB_IO = """\
/* A stand-in for the robot's drivers: sensors at rest at 0, torques dropped. */
#include <string.h>
#include "orccad_io.h"
int orc_io_open(const char *where) { return strcmp(where, "stub") == 0 ? 0 : -1; }
void orc_io_read_sensor(int k, orc_value *into)
{
    int i;
    into->present = 1;
    into->dim = ORC_ROBOT_PORTS[k].dim;
    for (i = 0; i < into->dim; i++) into->v[i] = 0.0;
}
void orc_io_write_actuator(int k, const orc_value *value) { (void)k; (void)value; }
long long orc_io_epoch_ns(long long fallback) { return fallback; }
void orc_io_publish(int m, const orc_mt *mt, long long released, long long overruns,
                    long long misses, long long events, double response_max_ns)
{
    (void)m; (void)mt; (void)released; (void)overruns; (void)misses; (void)events;
    (void)response_max_ns;
}
void orc_io_lateness(int m, double lateness_ns) { (void)m; (void)lateness_ns; }
void orc_io_reaction(const double *request, unsigned n_request, const double *reply,
                     unsigned n_reply)
{
    (void)request; (void)n_request; (void)reply; (void)n_reply;
}
int orc_io_jobs_wanted(void) { return 0; }
void orc_io_job(int m, const orc_job *job) { (void)m; (void)job; }
"""


def orccad(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "orccad_app.cli", *args], cwd=ROOT,
                          capture_output=True, text=True, timeout=600)


def _tools(where: Path, names: tuple[str, ...]) -> dict[str, str]:
    """An environment whose PATH holds only ``names`` (the build's tools), or a skip."""
    folder = where / "bin"
    folder.mkdir(exist_ok=True)
    for name in names:
        found = shutil.which(name)
        if found is None:
            pytest.skip(f"no {name} on this machine (apt-get install "
                        f"{'gcc-aarch64-linux-gnu' if 'aarch64' in name else 'gcc make'})")
        if not (folder / name).exists():
            (folder / name).symlink_to(found)
    assert shutil.which("python3", path=str(folder)) is None
    assert shutil.which("python", path=str(folder)) is None
    return {"PATH": str(folder)}


def _make(tree: Path, env: dict[str, str], *args: str) -> None:
    done = subprocess.run(["make", "-C", str(tree), "CFLAGS=-O2 -Werror", *args], env=env,
                          capture_output=True, text=True, timeout=600,
                          executable=shutil.which("make"))
    assert done.returncode == 0, done.stderr[-3000:]


def _report(result: subprocess.CompletedProcess) -> dict:
    assert "Traceback" not in result.stderr, result.stderr[-2000:]
    data = json.loads(result.stdout)
    data.pop("wall_time_s")
    data.pop("controller", None)
    return data


@pytest.fixture(scope="module")
def tree(tmp_path_factory) -> Path:
    """arm_recovery's controller tree, built by make with only the compiler on PATH."""
    where = tmp_path_factory.mktemp("tree")
    tree = where / "arm_recovery_controller"
    result = orccad("codegen", "missions/arm_recovery.orc", "--controller", "-o", str(tree))
    assert result.returncode == 0, result.stderr
    _make(tree, _tools(where, ("make", "cc", "as", "ld")))
    return tree


@pytest.fixture(scope="module")
def executive() -> dict:
    result = orccad("run", *RECOVERY, "--json")
    assert result.returncode == 0, result.stderr
    return _report(result)


def test_the_tree_holds_every_source_and_its_build_files(tree):
    names = {p.name for p in tree.iterdir()}
    assert {"Makefile", "CMakeLists.txt", "orccad_modules.c", "orc_mission.c",
            "orccad_automaton_binding.h", "orccad_rt_main.c", "orccad_lockstep.c",
            "orccad_io.h", "orccad_io_shm.c", "controller"} <= names
    assert "orccad_io.c" not in names  # the user's
    makefile = (tree / "Makefile").read_text()
    assert "CFLAGS ?= -O2" in makefile and "-lm -pthread" in makefile
    assert "python" not in makefile.lower()


def test_the_prebuilt_controller_ends_as_orccad_run(tree, executive):
    result = orccad("sil", *RECOVERY, "--lockstep", "--controller", str(tree / "controller"),
                    "--json")
    assert result.returncode == 0, result.stderr[-2000:]
    assert _report(result) == executive


def test_the_prebuilt_controller_in_real_time_runs_the_same_robot_tasks(tree, executive):
    result = orccad("sil", *RECOVERY, "--realtime", "--controller", str(tree / "controller"),
                    "--json")
    got = _report(result)
    assert got["status"] == "done", result.stderr[-2000:]
    assert [(t["name"], t["outcome"]) for t in got["robot_tasks"]] == \
        [(t["name"], t["outcome"]) for t in executive["robot_tasks"]]


def test_a_controller_of_another_mission_is_refused(tree):
    result = orccad("sil", "missions/arm_pid.orc", "--lockstep", "--controller",
                    str(tree / "controller"), "--until", "0.1")
    assert result.returncode in (1, 2) and "runs another table" in result.stderr
    assert "Traceback" not in result.stderr


@pytest.mark.parametrize("args, message", [
    (["--controller", "/nonexistent/controller"], "not an executable file"),
    (["--controller-wrapper", "qemu-aarch64"], "--controller-wrapper needs --controller"),
])
def test_bad_prebuilt_options_exit_2(args, message):
    result = orccad("sil", "missions/arm_pid.orc", "--lockstep", *args)
    assert result.returncode == 2 and message in result.stderr


def test_regenerating_keeps_the_users_io_and_refuses_other_files(tree):
    mine = tree / "orccad_io.c"
    mine.write_text(STUB_IO)
    try:
        result = orccad("codegen", "missions/arm_recovery.orc", "--controller", "-o", str(tree))
        assert result.returncode == 0, result.stderr
        assert mine.read_text() == STUB_IO and (tree / "controller").exists()
        (tree / "notes.txt").write_text("mine")
        result = orccad("codegen", "missions/arm_recovery.orc", "--controller", "-o", str(tree))
        assert result.returncode == 2 and "notes.txt" in result.stderr
    finally:
        (tree / "notes.txt").unlink(missing_ok=True)


def test_the_controller_alone_on_the_robot_takes_its_configuration_from_the_command_line(
        tree, tmp_path):
    (tree / "orccad_io.c").write_text(STUB_IO)
    _make(tree, _tools(tmp_path, ("make", "cc", "as", "ld")), "robot")
    robot = str(tree / "robot")
    done = subprocess.run([robot, "--io", "stub", "--until", "0.2"], capture_output=True,
                          text=True, timeout=60)
    assert done.returncode == 1 and "mission timeout after 0.2 s" in done.stderr
    for bad in ([robot], [robot, "--io", "stub", "--until", "-1"], [robot, "--bogus"]):
        done = subprocess.run(bad, capture_output=True, text=True, timeout=60)
        assert done.returncode == 2 and ("usage" in done.stderr or "--until" in done.stderr)
    done = subprocess.run([robot, "--io", "elsewhere"], capture_output=True, text=True,
                          timeout=60)
    assert done.returncode == 2 and "cannot start (elsewhere)" in done.stderr


def test_what_still_needs_the_supervisor_is_said():
    source = load(str(ROOT / "missions" / "auv_waypoints.orc"))
    plan = plan_mission(source, select_mission(source, None))
    files = controller_tree(plan, mission_automaton(plan).program, "missions/auv_waypoints.orc")
    binding = files["orccad_automaton_binding.h"]  # its run-time arguments bound in C
    assert '#define ORC_AUTOMATON_SUPERVISOR ""' in binding
    assert "#define ORC_AUTOMATON_N_BINDS 8" in binding
    source = load(str(ROOT / "missions" / "arm_recovery.orc"))
    plan = plan_mission(source, select_mission(source, None))
    files = controller_tree(plan, mission_automaton(plan).program, "missions/arm_recovery.orc")
    assert '#define ORC_AUTOMATON_SUPERVISOR ""' in files["orccad_automaton_binding.h"]


@pytest.mark.parametrize("mission, until", [("arm_recovery", None), ("auv_survey", "30")])
def test_an_aarch64_build_under_qemu_ends_as_orccad_run(mission, until, tmp_path):
    if shutil.which("qemu-aarch64") is None:
        pytest.skip("no qemu-aarch64 on this machine (apt-get install qemu-user; .ci/run "
                    "installs it where apt exists)")
    env = _tools(tmp_path, ("make", "aarch64-linux-gnu-gcc", "aarch64-linux-gnu-as",
                            "aarch64-linux-gnu-ld"))
    tree = tmp_path / f"{mission}_aarch64"
    result = orccad("codegen", f"missions/{mission}.orc", "--controller", "-o", str(tree))
    assert result.returncode == 0, result.stderr
    _make(tree, env, "CC=aarch64-linux-gnu-gcc")
    head = subprocess.run(["file", str(tree / "controller")], capture_output=True, text=True)
    assert head.returncode != 0 or "aarch64" in head.stdout
    run = ["missions/arm_recovery.orc", "--inject", "TrackPID.TrackingLost@2.5"] \
        if mission == "arm_recovery" else [f"missions/{mission}.orc", "--until", until]
    expected = orccad("run", *run, "--json")
    got = orccad("sil", *run, "--lockstep", "--controller", str(tree / "controller"),
                 "--controller-wrapper", " ".join(QEMU), "--json")
    assert got.returncode == expected.returncode, got.stderr[-2000:]
    assert _report(got) == _report(expected)
