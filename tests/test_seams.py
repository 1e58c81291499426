"""Seams stay typed: names are looked up, not parsed back (issue 24).

- the mission's own signals are told from the ones the Robot-Task lowering adds by
  :class:`~orccad_app.robottask.signals.SignalRoles`, never by a dot in the name;
- a port's module is a field of :class:`~orccad_app.tcs.port.PortRef`, never the text before
  a name's last dot;
- ``orccad run`` is argument handling and rendering around the run façade: short functions.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "orccad_app"

#: Tests of a dot in a name, or a name cut at its last dot.
NAME_PARSING = re.compile(r"""["']\.["'] (?:not )?in |\.rsplit\(["']\.["']|"""
                          r"""\.endswith\(["']\.(?:raised|start|good_end|adjust)["']\)""")

ALLOWED = {
    "orccad_app/robottask/signals.py": "SignalRoles itself",
}
"""Files that may match :data:`NAME_PARSING`, and why."""

NOT_YET: set[str] = set()
"""Owned by the software-in-the-loop work, which moves to the façade's types on its own."""


def test_no_signal_name_is_told_by_a_dot_outside_signal_roles():
    found = []
    for path in sorted(PACKAGE.rglob("*.py")):
        relative = path.relative_to(ROOT).as_posix()
        if relative in ALLOWED or any(relative.startswith(p) for p in NOT_YET):
            continue
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            if NAME_PARSING.search(line):
                found.append(f"{relative}:{number}: {line.strip()}")
    assert not found, "names parsed instead of looked up:\n" + "\n".join(found)


def test_the_pattern_finds_what_it_is_meant_to():
    for line in ('if "." not in s.name', "x = name.rsplit('.', 1)[0]",
                 'if s.name.endswith(".raised")', "if '.' in name:"):
        assert NAME_PARSING.search(line), line
    assert not NAME_PARSING.search('path.endswith(".toml")')


def test_the_run_command_is_argument_handling_and_rendering():
    tree = ast.parse((PACKAGE / "commands" / "run.py").read_text(encoding="utf-8"))
    lengths = {node.name: node.end_lineno - node.lineno + 1 for node in ast.walk(tree)
               if isinstance(node, ast.FunctionDef) and node.end_lineno is not None}
    longest = max(lengths, key=lengths.__getitem__)
    assert lengths[longest] < 40, f"commands/run.py: {longest} has {lengths[longest]} lines"


def test_the_run_vocabulary_is_typed_and_reads_as_its_words():
    import json

    from orccad_app.campaign.adapter import RUN_STATUSES
    from orccad_app.mission.result import STATUSES, MissionStatus
    from orccad_app.robottask.labels import Phase

    assert STATUSES == tuple(MissionStatus)
    assert json.dumps([MissionStatus.RECOVERING]) == '["recovering"]'  # reports unchanged
    assert f"{MissionStatus.DONE}" == "done"
    assert RUN_STATUSES == (*STATUSES, "crashed")
    assert Phase.IDLE == 0 and [p.word for p in Phase] == ["idle", "waiting", "measuring",
                                                            "running"]


def test_observers_do_not_reach_into_the_simulation():
    """Trace, TUI, campaign, properties and ROS 2 read a run through MissionRun (its plants,
    faults, processor loads, missed jobs), never through ``MissionRun.sim``."""
    found = []
    for path in sorted(PACKAGE.rglob("*.py")):
        relative = path.relative_to(ROOT).as_posix()
        if relative.startswith(("orccad_app/mission/", "orccad_app/executive/")):
            continue
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            if re.search(r"(?<!self)\.sim\b", line):
                found.append(f"{relative}:{number}: {line.strip()}")
    assert not found, "\n".join(found)


def _python_files() -> list[Path]:
    return sorted([*PACKAGE.rglob("*.py"), *(ROOT / "plugins").rglob("*.py")])


def test_module_tasks_run_behind_one_backend_not_a_mission_run_subclass():
    """Where a Module-Task's job runs is the run's ModuleTaskBackend (in-process, lockstep,
    real time): no class subclasses MissionRun, and only the mission layer and the run
    façade construct one."""
    subclasses, made = [], []
    for path in _python_files():
        relative = path.relative_to(ROOT).as_posix()
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            if isinstance(node, ast.ClassDef):
                bases = {ast.unparse(base).rsplit(".", 1)[-1] for base in node.bases}
                if bases & {"MissionRun", "RobotTaskLifecycle"} and \
                        relative != "orccad_app/mission/run.py":
                    subclasses.append(f"{relative}:{node.lineno}: class {node.name}")
            elif isinstance(node, ast.Call) and isinstance(node.func, (ast.Name, ast.Attribute)):
                name = node.func.id if isinstance(node.func, ast.Name) else node.func.attr
                if name == "MissionRun" and not relative.startswith(
                        ("orccad_app/mission/", "orccad_app/session/")):
                    made.append(f"{relative}:{node.lineno}")
    assert not subclasses, "\n".join(subclasses)
    assert not made, "MissionRun made outside the mission layer and the façade:\n" + \
        "\n".join(made)


#: The words of :mod:`orccad_app.reactive.status` (the run's status vocabulary).
STATUS_WORDS = frozenset({"running", "done", "failed", "aborted", "recovering", "timeout"})

STATUS_MODULE = "orccad_app/reactive/status.py"

HOMONYMS = {
    "orccad_app/lang/transform_formula.py": (3, "the formula keywords done, failed, aborted: "
                                             "lang is below reactive (the grammar's words, "
                                             "tied to Status by the next test)"),
    "orccad_app/tui/widgets/orc_lexer.py": (3, "the same keywords, for the highlighter"),
    "orccad_app/tui/screens/campaign.py": (7, "a campaign command's state (idle, running, "
                                           "finished, interrupted, failed), not a run's"),
    "orccad_app/robottask/labels.py": (1, "Phase.ACTIVE's word for people"),
    "orccad_app/commands/check.py": (1, "the JSON count of failed properties"),
    "orccad_app/campaign/runner.py": (1, "PrefixCounts.done, an attribute in __slots__"),
    "orccad_app/lsp/lifecycle.py": (1, "the language server's lifecycle phase"),
}
"""Files that write a status word for another concept: how many times, and why."""


def _status_literals(path: Path) -> list[int]:
    tree = ast.parse(path.read_text(encoding="utf-8"))
    return sorted(node.lineno for node in ast.walk(tree)
                  if isinstance(node, ast.Constant) and node.value in STATUS_WORDS)


def test_status_words_are_written_only_where_the_status_enum_is_born():
    """``"done"``, ``"failed"``… are :class:`~orccad_app.reactive.status.Status` and
    :class:`~orccad_app.reactive.status.MissionStatus` members everywhere but their module
    (issue 36): a new literal fails here, as does one more in a file of :data:`HOMONYMS`."""
    found = []
    for path in sorted([*PACKAGE.rglob("*.py"), *(ROOT / "plugins").rglob("*.py")]):
        relative = path.relative_to(ROOT).as_posix()
        if relative == STATUS_MODULE:
            continue
        lines = _status_literals(path)
        allowed = HOMONYMS.get(relative, (0, ""))[0]
        if len(lines) != allowed:
            found.append(f"{relative}: {len(lines)} status words (allowed {allowed}) at lines "
                         + ", ".join(map(str, lines)))
    assert not found, "status words outside reactive/status.py:\n" + "\n".join(found)


def test_the_status_words_are_the_enums_values():
    from orccad_app.reactive.status import MissionStatus, Status

    assert {*Status, *MissionStatus} == STATUS_WORDS
    assert _status_literals(ROOT / STATUS_MODULE)  # the test reads what it counts


def test_the_formula_status_keywords_are_the_ended_statuses():
    from orccad_app.lang.parser import parse
    from orccad_app.reactive.status import Status

    for status in Status:
        if status is Status.RUNNING:
            continue
        text = f"property M.p: eventually {status};\n"
        formula = parse(text, "<t>").properties[0].formula
        assert formula.operand.status == status and Status(formula.operand.status) is status


TASK_ERROR_HOMONYMS = {
    "orccad_app/control/closed_loop.py": 2,  # a closed-loop record's column
    "orccad_app/control/laws/fast.py": 1,  # LawOutput's attribute e
    "orccad_app/lang/limits.py": 1,  # the exponent of a number's text
    "orccad_app/tui/screens/report.py": 1,  # a key binding
    "orccad_app/tui/screens/run.py": 1,  # a key binding
    "orccad_app/verify/stl.py": 2,  # the prefix of an event variable
}
"""Files that write ``"e"`` for something else than the task-error port, and how often."""


def test_the_task_error_port_is_named_once():
    """The control law's ``e`` output, read by observers, the run's tracking error and
    ``robot.e`` properties, is :data:`orccad_app.control.ports.TASK_ERROR` (the plugins'
    ``plugin_api.TASK_ERROR``) everywhere else (issue 36)."""
    found = []
    for path in _python_files():
        relative = path.relative_to(ROOT).as_posix()
        if relative == "orccad_app/control/ports.py":
            continue
        tree = ast.parse(path.read_text(encoding="utf-8"))
        lines = sorted(node.lineno for node in ast.walk(tree)
                       if isinstance(node, ast.Constant) and node.value == "e")
        if len(lines) != TASK_ERROR_HOMONYMS.get(relative, 0):
            found.append(f"{relative}: \"e\" at lines {', '.join(map(str, lines))}")
    assert not found, "the task-error port written as \"e\":\n" + "\n".join(found)
