"""``PREFIX_main.c``: a program that runs the generated automaton on an ORCCAD input script
and prints what ``orccad react --composed --jsonl`` prints (``main_template.c``, the generic
part, reads the interface through the ``PREFIX_inputs``/``PREFIX_outputs`` tables)."""

from __future__ import annotations

from importlib.resources import files

from orccad_app.codegen.cexpr import c_string
from orccad_app.codegen.generate import CProgram
from orccad_app.lang.limits import MAX_DURATION_NS

__all__ = ["main_source"]


def main_source(program: CProgram) -> str:
    """The text of ``PREFIX_main.c`` for ``program``."""
    template = files("orccad_app.codegen").joinpath("main_template.c").read_text("utf-8")
    types = ", ".join(c_string(s.decl.type or "") for s in program.interface.inputs) or '""'
    return (template.replace("@INPUT_TYPES@", types)
            .replace("@MAX_DURATION_NS@", str(MAX_DURATION_NS))
            .replace("@UP@", program.prefix.upper())
            .replace("@P@", program.prefix))
