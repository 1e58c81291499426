"""The proof of one document, in its own process (``python -m orccad_app.lsp.prove``): the
engine of ``orccad check`` on the editor's buffer, so that the server can cancel it (kill
the process) when the document changes or the budget is spent.

Reads one JSON object on stdin — ``path``, ``text``, ``buffers`` (real path → text of the
other open documents, for imports) and ``max_states`` — and writes one on stdout:
``{"verdicts": [...]}`` (one per mission and property: ``mission``, ``kind``, ``name``,
``holds``, ``message``, ``script``: the counterexample's ``.in`` text or ``null``) and
``signal_properties`` (per mission, the names left to runs), or ``{"error": {...}}`` (a
located error, as ``orccad check`` would print it). No pygls here.
"""

from __future__ import annotations

import json
import shlex
import sys

__all__ = ["prove", "main"]


def _script(path: str, mission, outcome) -> str:
    """The counterexample as ``orccad check --counterexample`` writes it."""
    header = [f"counterexample to {outcome.kind} {mission.name}.{outcome.name}: "
              f"{outcome.message}",
              f"replay: orccad react {shlex.quote(path)} --mission {mission.name} --composed "
              "--inputs SCRIPT"]
    if outcome.script.note:
        header.append(f"note: {outcome.script.note}")
    return outcome.script.text(header)


def prove(request: dict) -> dict:
    """The verdicts of every mission of the document described by ``request``."""
    from orccad_app.diagnostics import OrccadError
    from orccad_app.lang.parser import parse
    from orccad_app.lsp.documents import buffer_reader
    from orccad_app.pipeline import check_source
    from orccad_app.verify.checker import check_mission

    path, text = request["path"], request["text"]
    try:
        source = check_source(path, text, parse(text, path), None,
                              buffer_reader(request.get("buffers", {})))
        verdicts, left = [], {}
        for mission in source.program.missions:
            report = check_mission(source.program, mission,
                                   max_states=int(request.get("max_states", 20_000)))
            for outcome in report.outcomes:
                verdicts.append({
                    "mission": mission.name, "kind": outcome.kind, "name": outcome.name,
                    "holds": outcome.holds, "message": outcome.message,
                    "script": None if outcome.holds or outcome.script is None
                    else _script(path, mission, outcome)})
            left[mission.name] = [p.name for p in report.signal_properties]
        return {"verdicts": verdicts, "signal_properties": left}
    except OrccadError as error:
        where = error.location
        return {"error": {"message": error.message,
                          "file": where.file if where else None,
                          "line": where.line if where else 0,
                          "col": where.col if where else 0}}


def main() -> int:
    request = json.loads(sys.stdin.read())
    out = sys.stdout
    sys.stdout = sys.stderr  # a plugin printing must not garble the answer
    try:
        answer = prove(request)
    except RecursionError:
        answer = {"error": {"message": "nested too deeply to check", "file": None,
                            "line": 0, "col": 0}}
    out.write(json.dumps(answer))
    out.flush()
    return 0


if __name__ == "__main__":
    sys.exit(main())
