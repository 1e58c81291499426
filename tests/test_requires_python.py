"""``requires-python`` admits no Python where a core or test dependency does not install
(issue 28, 9: it admitted 3.13, where rtamt — now the test extra's reference for signal
properties — does not install)."""

from __future__ import annotations

import importlib.metadata
import re
import tomllib
from pathlib import Path

from packaging.requirements import Requirement
from packaging.specifiers import SpecifierSet

ROOT = Path(__file__).resolve().parents[1]


def test_requires_python_is_within_every_core_dependency_s() -> None:
    project = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]
    ours = SpecifierSet(project["requires-python"])
    candidates = [f"3.{minor}.0" for minor in range(8, 20)]
    for line in project["dependencies"] + project["optional-dependencies"]["test"]:
        name = Requirement(line).name
        theirs = importlib.metadata.metadata(name).get("Requires-Python")
        if not theirs:
            continue
        allowed = SpecifierSet(re.sub(r"\s+", "", theirs))
        wrong = [v for v in candidates if v in ours and v not in allowed]
        assert not wrong, f"requires-python {ours} admits {wrong}, where {name} needs {theirs}"
