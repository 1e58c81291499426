"""The code cites only documents that are in the repository: every ``docs/NAME.md`` named in
a source file exists, and every section it names (``docs/design.md, *Reactions*``) is a
heading of that document (or the start of one), or one of its bold labels."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SOURCES = sorted(p for folder in ("orccad_app", "plugins", "bench")
                 for p in (ROOT / folder).rglob("*") if p.suffix in {".py", ".lark", ".tcss"})
_DOC = re.compile(r"docs/([\w-]+\.md)")
_SECTION = re.compile(r"docs/([\w-]+\.md),?\s*\(?\*([^*]+)\*")


def _citations():
    for path in SOURCES:
        text = path.read_text(encoding="utf-8")
        for doc in sorted(set(_DOC.findall(text))):
            yield pytest.param(path, doc, None, id=f"{path.relative_to(ROOT)}: {doc}")
        for doc, section in sorted(set(_SECTION.findall(text))):
            yield pytest.param(path, doc, section, id=f"{path.relative_to(ROOT)}: {doc} {section}")


def _headings(doc: Path) -> set[str]:
    """The headings of a document and its bold run-in labels (``- **Fresh ports.** …``)."""
    text = doc.read_text("utf-8")
    headings = {m.group(1).strip() for m in re.finditer(r"^#+\s+(.*)$", text, re.M)}
    labels = {m.group(1).strip().rstrip(".:") for m in re.finditer(r"\*\*([^*]+)\*\*", text)}
    return headings | labels


@pytest.mark.parametrize("source,doc,section", list(_citations()))
def test_cited_document_and_section_exist(source, doc, section):
    target = ROOT / "docs" / doc
    assert target.is_file(), f"{source} cites docs/{doc}, which does not exist"
    if section is not None:
        # a citation may shorten a heading to its start ("Idle behaviour" for "Idle
        # behaviour: what holds a robot between tasks")
        assert any(h.lower().startswith(section.lower()) for h in _headings(target)), (
            f"{source} cites a section '{section}' of docs/{doc}")


def test_the_code_cites_the_docs():
    assert len(list(_citations())) >= 10
