"""docs/language.md lists the reserved keywords: exactly the parser's (a new keyword must be
documented, and a documented one must be reserved)."""

from __future__ import annotations

import re
from pathlib import Path

from orccad_app.lang import keywords

DOC = Path(__file__).resolve().parents[2] / "docs" / "language.md"


def test_the_documented_keywords_are_the_reserved_ones():
    text = DOC.read_text(encoding="utf-8")
    found = re.search(r"Keywords are reserved and cannot name anything:\s*`([^`]*)`", text)
    assert found, "docs/language.md no longer lists the keywords"
    assert set(found.group(1).split()) == set(keywords())
