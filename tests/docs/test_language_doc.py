"""Every example of docs/language.md is parsed, compiled and, where a trace follows, replayed.

- an ``orc`` block is a whole file: every mission in it must compile;
- a ``react`` block after it is a trace, one instant per line, ``inputs -> outputs``;
- an ``orc-error`` block must be rejected with exit status 2 and the message of the ``text``
  block after it (``test.orc`` stands for the file's name);
- an ``orc`` block whose first line is ``// file: PATH`` is a library file: written at
  ``PATH`` (next to ``test.orc``) for every later example (which may import it), and its
  missions compiled from there.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from orccad_app.cli import main

DOC = Path(__file__).resolve().parents[2] / "docs" / "language.md"
_BLOCK = re.compile(r"```([a-z-]*)\n(.*?)```", re.S)
_LIBRARY = re.compile(r"// file: (\S+)\n")


def _examples():
    blocks = [(m.group(1), m.group(2)) for m in _BLOCK.finditer(DOC.read_text(encoding="utf-8"))]
    libraries: dict[str, str] = {}
    for i, (kind, text) in enumerate(blocks):
        following = blocks[i + 1] if i + 1 < len(blocks) else (None, "")
        library = _LIBRARY.match(text) if kind == "orc" else None
        if library:
            libraries[library.group(1)] = text
            yield pytest.param(kind, text, None, dict(libraries), library.group(1),
                               id=f"lib-{i}")
        elif kind == "orc":
            trace = following[1] if following[0] == "react" else None
            yield pytest.param(kind, text, trace, dict(libraries), "test.orc", id=f"orc-{i}")
        elif kind == "orc-error":
            yield pytest.param(kind, text, following[1], dict(libraries), "test.orc",
                               id=f"error-{i}")


def _mission_names(source: str) -> list[str]:
    return re.findall(r"^mission\s+(\w+)", source, re.M)


@pytest.mark.parametrize("kind,source,expected,libraries,file", list(_examples()))
def test_language_doc_example(kind, source, expected, libraries, file, tmp_path, capsys,
                              monkeypatch):
    monkeypatch.chdir(tmp_path)
    for path, text in libraries.items():
        Path(path).parent.mkdir(parents=True, exist_ok=True)
        Path(path).write_text(text, encoding="utf-8")
    Path(file).write_text(source, encoding="utf-8")
    if kind == "orc-error":
        assert main(["compile", file]) == 2
        assert expected.strip().splitlines()[0] in capsys.readouterr().err
        return
    for name in _mission_names(source):
        assert main(["compile", file, "--mission", name]) == 0, capsys.readouterr().err
    if expected is None:
        return
    lines = [line.split("->") for line in expected.strip("\n").splitlines()]
    Path("trace.in").write_text("\n".join(left.strip() for left, _ in lines) + "\n",
                                encoding="utf-8")
    capsys.readouterr()
    # a file with sub-missions runs its last mission; 1 is a mission ending failed (`fail`)
    assert main(["react", file, "--mission", _mission_names(source)[-1],
                 "--inputs", "trace.in", "--jsonl"]) in (0, 1)
    import json
    records = [json.loads(line) for line in capsys.readouterr().out.splitlines()]
    got = [" ".join(f"{o}({r['values'][o]})" if o in r["values"] else o for o in r["outputs"])
           or "-" for r in records]
    assert got == [right.strip() for _, right in lines]


def test_the_doc_has_examples():
    assert len(list(_examples())) >= 10
