"""Shared fixtures of the codegen tests: every shipped mission generated once per session."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path


from orccad_app.codegen.generate import CProgram
from orccad_app.codegen.mission import default_prefix, generate_mission
from orccad_app.pipeline import compose_mission, load
from orccad_app.robottask.composition import Composition

ROOT = Path(__file__).resolve().parents[2]
MISSIONS = ROOT / "missions"
SCRIPTS = Path(__file__).parent / "scripts"


def _shipped() -> list[tuple[str, str]]:
    found = []
    for path in sorted(MISSIONS.glob("*.orc")):
        for mission in load(path).program.missions:
            found.append((path.stem, mission.name))
    return found


#: (file stem, mission) of every mission in missions/*.orc
SHIPPED = _shipped()


@dataclass(frozen=True)
class Generated:
    composition: Composition
    program: CProgram


_CACHE: dict[tuple[str, str], Generated] = {}


def generated(stem: str, mission: str) -> Generated:
    """The composed automaton of a shipped mission and its C (made once per session)."""
    key = (stem, mission)
    if key not in _CACHE:
        source = load(MISSIONS / f"{stem}.orc")
        composition = compose_mission(source, source.program.mission(mission))
        _CACHE[key] = Generated(composition,
                                generate_mission(composition, default_prefix(mission)))
    return _CACHE[key]


#: lines printed at the end of the session (tests/codegen/test_coverage.py)
COVERAGE: list[str] = []


def pytest_terminal_summary(terminalreporter):
    if COVERAGE:
        terminalreporter.section("codegen: transition coverage of the differential tests")
        for line in COVERAGE:
            terminalreporter.write_line(line)
