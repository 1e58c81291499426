"""The VS Code extension's TextMate grammar (editors/vscode/), tokenized by a TextMate
engine (textmate-grammar-python, a port of vscode-textmate) on every shipped mission and
compared with the language's own lexer: keywords, durations, numbers, strings, protocols and
comments get their scopes, names are never taken for keywords."""

from __future__ import annotations

import json
import logging
import re
from pathlib import Path

import pytest

from orccad_app.lang.ast_robottask import PROTOCOLS
from orccad_app.lang.parser import keywords, literal_terminals
from orccad_app.lsp.tokens import tokens

ROOT = Path(__file__).resolve().parents[2]
VSCODE = ROOT / "editors" / "vscode"
GRAMMAR = json.loads((VSCODE / "syntaxes" / "orccad.tmLanguage.json").read_text())
SHIPPED = sorted((ROOT / "missions").rglob("*.orc"))


@pytest.fixture(scope="module")
def engine(tmp_path_factory):
    """The TextMate engine with our grammar (imported from a scratch folder: the package
    makes a cache folder in the current directory when imported)."""
    import os
    here = os.getcwd()
    os.chdir(tmp_path_factory.mktemp("textmate"))
    try:
        base = pytest.importorskip("textmate_grammar.parsers.base")
    finally:
        os.chdir(here)
    logging.getLogger("textmate_grammar").setLevel(logging.ERROR)
    return base.LanguageParser(GRAMMAR)


def _scopes(engine, text: str) -> dict[int, list[tuple[int, int, list[str]]]]:
    """Line → its segments (start, end, scopes)."""
    out: dict[int, list[tuple[int, int, list[str]]]] = {}
    for (line, col), segment, scopes in engine.parse_string(text).flatten():
        for number, part in enumerate(segment.split("\n")):
            start = col if number == 0 else 0
            out.setdefault(line + number, []).append((start, start + len(part), scopes))
    return out


def _scope_at(segments, line: int, col: int) -> list[str]:
    for start, end, scopes in segments.get(line, ()):
        if start <= col < end:
            return scopes
    return []


_EXPECTED = {"DURATION": "constant.numeric.duration", "INT": "constant.numeric",
             "FLOAT": "constant.numeric", "STRING": "string.quoted",
             "PROTOCOL": "constant.language.protocol"}
_KEYWORD_SCOPES = ("keyword.", "storage.type", "support.function.atom", "constant.language")


@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: p.name)
def test_the_grammar_agrees_with_the_lexer_on_every_shipped_mission(engine, path: Path):
    text = path.read_text()
    segments = _scopes(engine, text)
    literals = literal_terminals()
    words = keywords()
    checked = 0
    for tok in tokens(text):
        scopes = " ".join(_scope_at(segments, tok.line, tok.col))
        if tok.kind in _EXPECTED:
            assert _EXPECTED[tok.kind] in scopes, (path.name, tok, scopes)
        elif literals.get(tok.kind) in words:
            assert any(s in scopes for s in _KEYWORD_SCOPES), (path.name, tok, scopes)
        elif tok.kind == "NAME" and "constant.language.protocol" in scopes:
            # the standalone lexer reads `asyn/syn` as names around a slash (the parser's
            # contextual lexer reads one PROTOCOL there)
            assert re.search(rf"\b(\w+/{tok.text}|{tok.text}/\w+)\b", text.split("\n")[tok.line])
            assert any(tok.text in p.split("/") for p in PROTOCOLS)
        elif tok.kind == "NAME":
            assert not any(s in scopes for s in _KEYWORD_SCOPES), (path.name, tok, scopes)
            assert "comment" not in scopes and "string" not in scopes, (path.name, tok)
        checked += 1
    for number, line in enumerate(text.split("\n")):
        code = re.sub(r'"([^"\\]|\\.)*"', lambda m: " " * len(m.group()), line)
        if "//" in code:
            col = code.index("//")
            assert "comment.line" in " ".join(_scope_at(segments, number, col)), (path.name,
                                                                                   number)
    assert checked > 20


def test_every_keyword_of_the_language_has_a_keyword_scope():
    patterns = [p["match"] for p in GRAMMAR["repository"]["keywords"]["patterns"]]
    for word in sorted(keywords()):
        assert any(re.fullmatch(p, word) for p in patterns), word


def test_the_extension_declares_the_language_and_its_grammar():
    package = json.loads((VSCODE / "package.json").read_text())
    language = package["contributes"]["languages"][0]
    assert language["id"] == "orccad" and language["extensions"] == [".orc"]
    grammar = package["contributes"]["grammars"][0]
    assert grammar["scopeName"] == GRAMMAR["scopeName"] == "source.orccad"
    assert (VSCODE / grammar["path"]).is_file()
    assert (VSCODE / language["configuration"]).is_file()
    assert package["main"] == "./extension.js" and (VSCODE / "extension.js").is_file()
    assert package["contributes"]["configuration"]["properties"][
        "orccad.server.command"]["default"] == ["orccad", "lsp"]
