"""docs/glossary.md names real code: every ``path.py`` it cites exists under orccad_app/, and
every ``path.py`` ``Name`` pair is a name defined in that module (so a rename that forgets the
glossary fails here)."""

from __future__ import annotations

import importlib
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
GLOSSARY = (ROOT / "docs" / "glossary.md").read_text(encoding="utf-8")
_PATH = re.compile(r"`([a-z_]+(?:/[a-z_]+)*\.py)`")
_PAIR = re.compile(r"`([a-z_]+(?:/[a-z_]+)*\.py)` `([A-Za-z_][A-Za-z0-9_]*)")


@pytest.mark.parametrize("path", sorted(set(_PATH.findall(GLOSSARY))))
def test_cited_module_exists(path):
    assert (ROOT / "orccad_app" / path).is_file(), path


@pytest.mark.parametrize("path,name", sorted(set(_PAIR.findall(GLOSSARY))))
def test_cited_name_is_defined_in_its_module(path, name):
    module = importlib.import_module("orccad_app." + path.removesuffix(".py").replace("/", "."))
    assert hasattr(module, name), f"{path} defines no {name}"


def test_the_glossary_cites_code():
    assert len(_PAIR.findall(GLOSSARY)) >= 30
