"""``from "PATH" import M, …;``: missions of another file (orccad_app/lang/imports.py).

Each error is a located ``OrccadError`` (exit status 2 from the CLI), in the file where the
problem is (the imported file for its own errors) with a note at the ``import``.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from orccad_app.cli import main
from orccad_app.lang import ast, imports
from orccad_app.lang.walk import nodes
from orccad_app.pipeline import load

GREET = """\
// a library of one sub-mission
mission Greet [input Go; output Hello] {
    await Go;
    emit Hello;
    await Go;
}
"""

MAIN = """\
from "lib/greet.orc" import Greet;

mission Main {
    input Go;
    output Hi;
    run mission Greet [Hello / Hi];
    run mission Greet [Hello / Hi];
}
"""


def _write(root: Path, files: dict[str, str]) -> None:
    for name, text in files.items():
        path = root / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")


def _error(tmp_path: Path, capsys, files: dict[str, str], command: str = "compile") -> str:
    """The stderr of a command on ``main.orc`` that must fail with status 2."""
    _write(tmp_path, files)
    assert main([command, str(tmp_path / "main.orc")]) == 2
    err = capsys.readouterr().err
    assert "Traceback" not in err
    return err


def test_an_imported_mission_runs_as_a_sub_mission(tmp_path, capsys):
    _write(tmp_path, {"lib/greet.orc": GREET, "main.orc": MAIN,
                      "in.txt": "Go\nGo\nGo\nGo\n"})
    assert main(["react", str(tmp_path / "main.orc"), "--inputs", str(tmp_path / "in.txt"),
                 "--jsonl"]) == 0
    outputs = [json.loads(line)["outputs"] for line in capsys.readouterr().out.splitlines()]
    assert outputs == [[], ["Hi"], [], ["Hi"]]


def test_the_path_is_relative_to_the_importing_file_not_the_working_folder(
        tmp_path, capsys, monkeypatch):
    _write(tmp_path, {"lib/greet.orc": GREET, "main.orc": MAIN})
    (tmp_path / "elsewhere").mkdir()
    monkeypatch.chdir(tmp_path / "elsewhere")
    assert main(["compile", "../main.orc"]) == 0, capsys.readouterr().err


def test_a_missing_file_is_located_at_the_import(tmp_path, capsys):
    err = _error(tmp_path, capsys, {"main.orc": MAIN})
    assert f'{tmp_path / "main.orc"}:1:6: error: cannot import "lib/greet.orc": ' in err
    assert "no such file" in err


def test_an_import_cycle_is_an_error(tmp_path, capsys):
    err = _error(tmp_path, capsys, {
        "main.orc": 'from "lib/a.orc" import A;\nmission Main { run mission A; }\n',
        "lib/a.orc": 'from "b.orc" import B;\nmission A { run mission B; }\n',
        "lib/b.orc": 'from "a.orc" import A;\nmission B { nothing; }\n'})
    assert f"{tmp_path / 'lib' / 'b.orc'}:1:6: error: import cycle: " in err
    assert "a.orc -> " in err and "b.orc -> " in err


def test_a_file_importing_itself_is_a_cycle(tmp_path, capsys):
    err = _error(tmp_path, capsys, {
        "main.orc": 'from "main.orc" import Main;\nmission Main { nothing; }\n'})
    assert "main.orc:1:6: error: import cycle" in err


def test_an_imported_mission_clashing_with_a_local_one_is_an_error(tmp_path, capsys):
    err = _error(tmp_path, capsys, {"lib/greet.orc": GREET, "main.orc": MAIN.replace(
        "mission Main {", "mission Greet { nothing; }\nmission Main {")})
    assert (f"{tmp_path / 'main.orc'}:1:29: error: mission 'Greet' imported from "
            "lib/greet.orc clashes with the mission 'Greet' of this file") in err
    assert f"{tmp_path / 'main.orc'}:3:1: note: the mission of this file" in err


def test_a_parse_error_in_the_imported_file_names_that_file_and_line(tmp_path, capsys):
    err = _error(tmp_path, capsys, {"lib/greet.orc": GREET.replace("emit Hello;", "emit ;"),
                                    "main.orc": MAIN})
    assert f"{tmp_path / 'lib' / 'greet.orc'}:4:10: error:" in err
    assert f"{tmp_path / 'main.orc'}:1:1: note: imported here" in err


def test_a_name_error_in_the_imported_file_is_located_there(tmp_path, capsys):
    err = _error(tmp_path, capsys, {"lib/greet.orc": GREET.replace("await Go;\n    emit",
                                                                   "await Gone;\n    emit"),
                                    "main.orc": MAIN})
    assert f"{tmp_path / 'lib' / 'greet.orc'}:3:11: error: undeclared signal 'Gone'" in err


def test_importing_a_robot_task_is_refused(tmp_path, capsys):
    library = ("robot arm : arm3dof;\nrobottask Home() on arm {\n"
               "    task_function joint_tracking(trajectory = min_jerk(goal = [0.0, 0.0, 0.0],"
               " duration = 1.0));\n    law pid(kp = 400.0, kv = 40.0);\n}\n")
    err = _error(tmp_path, capsys, {
        "lib/arm.orc": library,
        "main.orc": 'from "lib/arm.orc" import Home;\nmission Main { nothing; }\n'})
    assert (f"{tmp_path / 'main.orc'}:1:27: error: 'Home' is a Robot-Task of "
            f"{tmp_path / 'lib' / 'arm.orc'}, not a mission") in err


def test_importing_an_unknown_name_lists_the_missions(tmp_path, capsys):
    err = _error(tmp_path, capsys, {"lib/greet.orc": GREET, "main.orc": MAIN.replace(
        "import Greet;", "import Greet, Wave;")})
    assert "main.orc:1:36: error:" in err
    assert "has no mission 'Wave' (its missions: Greet)" in err


def test_an_imported_mission_may_not_use_a_file_level_signal_of_its_file(tmp_path, capsys):
    library = "input Go;\nmission Greet [output Hello] { await Go; emit Hello; }\n"
    err = _error(tmp_path, capsys, {"lib/greet.orc": library, "main.orc": MAIN})
    assert f"{tmp_path / 'lib' / 'greet.orc'}:2:38: error: undeclared signal 'Go'" in err
    assert "an imported mission sees only its own signals" in err


def test_a_robot_of_the_importer_must_be_the_library_s(tmp_path, capsys):
    homing = Path("missions/lib/homing.orc").resolve().read_text(encoding="utf-8")
    err = _error(tmp_path, capsys, {
        "lib/homing.orc": homing,
        "main.orc": 'from "lib/homing.orc" import Homing;\nrobot arm : auv;\n'
                    'mission Main { run mission Homing; }\n'})
    assert "robot 'arm' of" in err and "differs from the robot 'arm' of this file" in err


def test_a_robot_task_brought_by_an_import_clashes_with_a_local_one(tmp_path, capsys):
    homing = Path("missions/lib/homing.orc").resolve().read_text(encoding="utf-8")
    local = homing[homing.index("robottask Home"):]
    err = _error(tmp_path, capsys, {
        "lib/homing.orc": homing,
        "main.orc": 'from "lib/homing.orc" import Homing;\nrobot arm : arm3dof;\n' + local
                    + 'mission Main { run mission Homing; }\n'})
    assert ("Robot-Task 'Home' imported from lib/homing.orc (it comes with mission 'Homing') "
            "clashes with the Robot-Task 'Home' of this file") in err


def test_the_same_mission_reached_through_two_imports_is_loaded_once(tmp_path, capsys):
    _write(tmp_path, {
        "lib/greet.orc": GREET,
        "lib/twice.orc": 'from "greet.orc" import Greet;\n'
                         'mission Twice [input Go; output Hello] {\n'
                         '    run mission Greet; run mission Greet;\n}\n',
        "main.orc": 'from "lib/twice.orc" import Twice;\nfrom "lib/./greet.orc" import Greet;\n'
                    'mission Main { input Go; output Hello; run mission Twice; '
                    'run mission Greet; }\n'})
    source = load(tmp_path / "main.orc")
    assert [m.name for m in source.program.imported_missions] == ["Twice", "Greet"]
    assert len(source.imported) == 2
    assert main(["compile", str(tmp_path / "main.orc")]) == 0, capsys.readouterr().err


def test_import_depth_and_count_are_budgeted(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(imports, "MAX_IMPORT_DEPTH", 2)
    files = {"main.orc": 'from "l1.orc" import M1;\nmission Main { run mission M1; }\n'}
    for level in range(1, 4):
        files[f"l{level}.orc"] = (f'from "l{level + 1}.orc" import M{level + 1};\n'
                                  f"mission M{level} {{ run mission M{level + 1}; }}\n")
    files["l4.orc"] = "mission M4 { nothing; }\n"
    err = _error(tmp_path, capsys, files)
    assert "l2.orc:1:6: error: imports nest deeper than 2 files" in err
    monkeypatch.setattr(imports, "MAX_IMPORT_DEPTH", 16)
    monkeypatch.setattr(imports, "MAX_IMPORTED_FILES", 3)
    err = _error(tmp_path, capsys, files)
    assert "l3.orc:1:6: error: more than 3 files imported" in err


def test_the_digest_covers_the_imported_files(tmp_path):
    _write(tmp_path, {"lib/greet.orc": GREET, "main.orc": MAIN})
    before = load(tmp_path / "main.orc").digest
    assert load(tmp_path / "main.orc").digest == before
    (tmp_path / "lib" / "greet.orc").write_text(GREET.replace("await Go;\n}", "pause;\n}"),
                                                 encoding="utf-8")
    assert load(tmp_path / "main.orc").digest != before


def test_a_file_without_imports_keeps_its_text_digest(tmp_path):
    import hashlib
    (tmp_path / "m.orc").write_text("mission M { nothing; }\n", encoding="utf-8")
    assert load(tmp_path / "m.orc").digest == hashlib.sha256(
        b"mission M { nothing; }\n").hexdigest()


@pytest.mark.parametrize("form", ['from lib import Greet;', 'from "lib/greet.orc" import ;',
                                  'from "lib/greet.orc" import mission Greet;'])
def test_malformed_imports_are_syntax_errors(tmp_path, capsys, form):
    err = _error(tmp_path, capsys, {"lib/greet.orc": GREET,
                                    "main.orc": form + "\nmission Main { nothing; }\n"})
    assert "main.orc:1:" in err and "error:" in err


def test_the_same_files_give_the_same_automaton(tmp_path, capsys):
    _write(tmp_path, {"lib/greet.orc": GREET, "main.orc": MAIN})
    outputs = []
    for _ in range(2):
        assert main(["compile", str(tmp_path / "main.orc"), "--format", "json"]) == 0
        outputs.append(capsys.readouterr().out)
    assert outputs[0] == outputs[1]


def test_a_library_file_runs_alone(capsys):
    assert main(["run", "missions/lib/homing.orc", "--json"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert report["status"] == "done"
    assert [(t["name"], t["outcome"]) for t in report["robot_tasks"]] == [("Home", "good_end")]


def test_arm_recovery_homes_through_the_library_twice():
    source = load("missions/arm_recovery.orc")
    mission = source.program.missions[0]
    calls = [n.mission for n in nodes(mission) if isinstance(n, ast.RunMission)]
    assert calls.count("Homing") == 2 and calls.count("Parking") == 1
    assert {f.path for f in source.imported} == {"missions/lib/homing.orc",
                                                 "missions/lib/parking.orc"}
    assert source.program.robottask("Home").loc.file == "missions/lib/homing.orc"


def test_sub_missions_on_one_robot_in_parallel_branches_are_a_resource_conflict(tmp_path,
                                                                               capsys):
    lib = Path("missions/lib").resolve()
    err = _error(tmp_path, capsys, {
        "lib/homing.orc": (lib / "homing.orc").read_text(encoding="utf-8"),
        "lib/parking.orc": (lib / "parking.orc").read_text(encoding="utf-8"),
        "main.orc": 'from "lib/homing.orc" import Homing;\n'
                    'from "lib/parking.orc" import Parking;\n'
                    "mission M {\n"
                    "    par { run mission Homing; } || { run mission Parking; }\n}\n"})
    assert (f"{tmp_path / 'main.orc'}:4:38: error: resource conflict: Robot-Tasks Home and "
            "Park both use robot 'arm' and may run in parallel branches (Park in sub-mission "
            "'Parking')") in err
    assert f"{tmp_path / 'lib' / 'homing.orc'}:9:5: note: Home runs here" in err


def test_a_campaign_sees_an_edited_library(tmp_path):
    from orccad_app.campaign.adapter import CompiledMission

    _write(tmp_path, {"lib/greet.orc": GREET, "main.orc": MAIN})
    before = CompiledMission(str(tmp_path / "main.orc")).digest
    (tmp_path / "lib" / "greet.orc").write_text(GREET + "// edited\n", encoding="utf-8")
    assert CompiledMission(str(tmp_path / "main.orc")).digest != before  # resume refuses
