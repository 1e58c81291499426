"""What each run site starts, for the generated C: its Robot-Task and how it gives each of the
task's parameters (issue 35 item 5; docs/deploy.md, *What a site starts*).

A hand-written control loop steps the automaton and must start the right Module-Tasks with the
right parameters when a site's start output is emitted: ``run Reach(goal = A)`` and ``run
Reach(goal = B)`` start one Robot-Task with two goals. :func:`site_infos` reads, per run site,
every parameter of its Robot-Task with its value and how the site gives it — a constant written
at the site, the task's default, or a run-time argument computed in the instant the task starts
(carried by the argument output ``X.arg.P``, whose index in ``PREFIX_outputs`` the table
gives); :func:`site_tables` writes them as ``PREFIX_site_info[]``, :func:`site_comment` as the
header's comment, :func:`phase_columns` as the phase table's column legend.
"""

from __future__ import annotations

import enum
import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Any

from orccad_app.codegen.cexpr import c_comment, c_string
from orccad_app.diagnostics import NOWHERE, SourceLocation
from orccad_app.robottask.application import RunSite
from orccad_app.robottask.values import task_arguments

__all__ = ["Given", "SiteParam", "SiteInfo", "site_infos", "site_tables", "site_comment",
           "phase_columns", "SITE_TYPES"]


class Given(enum.IntEnum):
    """How a run site gives a parameter of its Robot-Task (``orccad_site_param.given``)."""

    DEFAULT = 0
    """Not written at the site: the Robot-Task's default."""
    CONSTANT = 1
    """A constant written at the site (``run TrackPID(kp = 600.0)``)."""
    AT_START = 2
    """A run-time argument (``run GoTo(target = ?Waypoint)``): computed in the instant the task
    starts, carried by an argument output; the value given is the nominal one (the default)
    the control scheme was checked with."""


_KINDS = {bool: "ORCCAD_BOOL", int: "ORCCAD_INT", float: "ORCCAD_FLOAT", str: "ORCCAD_STRING"}


@dataclass(frozen=True)
class SiteParam:
    """One parameter of a site's Robot-Task.

    :param name: the parameter.
    :param given: how the site gives it.
    :param value: its value (the nominal one for :attr:`Given.AT_START`): a bool, int, float,
        string or list of numbers (a vector); a duration is an int of nanoseconds.
    :param output: for :attr:`Given.AT_START`, the argument output carrying it (``X.arg.P``).
    """

    name: str
    given: Given
    value: Any
    output: str | None = None

    @property
    def kind(self) -> str:
        """Its ``enum orccad_value_kind`` constant."""
        if isinstance(self.value, list):
            return "ORCCAD_FLOAT_VECTOR"
        return _KINDS.get(type(self.value), "ORCCAD_FLOAT")

    @property
    def numbers(self) -> list[float] | None:
        """Its value as numbers (a bool as 0/1), ``None`` for a string."""
        value = self.value
        if isinstance(value, str):
            return None
        return [float(v) for v in (value if isinstance(value, list) else [value])]

    @property
    def text(self) -> str:
        """Its value as the report writes it (``600``, ``[1, 1, 1]``, ``"north"``)."""
        return _text(self.value)


def _text(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return f"{value:g}"
    if isinstance(value, list):
        return "[" + ", ".join(_text(v) for v in value) + "]"
    if isinstance(value, str):
        return '"' + value + '"'
    return str(value)


@dataclass(frozen=True)
class SiteInfo:
    """One run site: its number, Robot-Task, ``run`` statement's location and parameters."""

    number: int
    task: str
    loc: SourceLocation = NOWHERE
    params: tuple[SiteParam, ...] = ()

    def call_text(self) -> str:
        """``Home(goal = [1, 1, 1])``: the parameters the site writes, a run-time one as
        ``target = <at start>``."""
        written = [f"{p.name} = {'<at start>' if p.given is Given.AT_START else p.text}"
                   for p in self.params if p.given is not Given.DEFAULT]
        return f"{self.task}({', '.join(written)})"


SITE_TYPES = """\
/* How a run site gives a parameter of its Robot-Task (orccad_site_param.given). */
enum orccad_given {
    ORCCAD_GIVEN_DEFAULT = 0,  /* not written at the site: the Robot-Task's default */
    ORCCAD_GIVEN_CONSTANT = 1, /* a constant written at the site */
    ORCCAD_GIVEN_AT_START = 2  /* computed in the instant the task starts: the argument output
                                  `output` carries it (value: the nominal default) */
};

/* One parameter of a run site's Robot-Task: its name, how the site gives it, its value kind
   (enum orccad_value_kind) and size (components), its value as `size` numbers (a bool as 0/1,
   a duration in ns; NULL for a string), its value as text (a string's text in quotes), and
   for ORCCAD_GIVEN_AT_START the index in PREFIX_outputs of the output carrying it (else -1). */
typedef struct {
    const char *name;
    int given;
    int kind;
    int size;
    const double *value;
    const char *text;
    int output;
} orccad_site_param;

/* One run site (PREFIX_site_info[site], site numbers in source order): the Robot-Task it
   starts, where its run statement is, and every parameter of the task as the site gives it. */
typedef struct {
    const char *task;
    const char *file;
    int line;
    int col;
    int param_count;
    const orccad_site_param *params;
} orccad_site_info;
"""
"""The C types of the site table (in the headers' shared block)."""


def site_infos(sites: Iterable[RunSite]) -> tuple[SiteInfo, ...]:
    """Every run site's :class:`SiteInfo`, in number order."""
    infos = []
    for site in sorted(sites, key=lambda s: s.number):
        task = site.robottask
        written = set()
        for index, arg in enumerate(site.stmt.args):
            name = arg.name if arg.name is not None else task.params[index].name
            written.add(name)
        at_start = {argument.param: argument.signal for argument in site.arguments}
        nominal = task_arguments(task, site.stmt.args)  # run-time ones: their defaults
        params = []
        for param in task.params:
            value = nominal[param.name]
            if param.name in at_start:
                given, output = Given.AT_START, at_start[param.name]
            else:
                given = Given.CONSTANT if param.name in written else Given.DEFAULT
                output = None
            params.append(SiteParam(param.name, given, _plain(value), output))
        infos.append(SiteInfo(site.number, task.name, site.loc, tuple(params)))
    return tuple(infos)


def _plain(value: Any) -> Any:
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if hasattr(value, "tolist"):
        return _plain(value.tolist())
    return value


def _double(value: float) -> str:
    if not math.isfinite(value):
        return "0.0 /* not finite */"
    text = repr(value)
    return f"({text})" if text.startswith("-") else text


def site_tables(prefix: str, sites: tuple[SiteInfo, ...],
                outputs: Mapping[str, int]) -> list[str]:
    """The C definitions of ``PREFIX_site_info[]`` (``outputs``: each output's index in
    ``PREFIX_outputs``)."""
    out: list[str] = []
    rows = []
    for site in sites:
        entries = []
        for k, param in enumerate(site.params):
            numbers = param.numbers
            values = "NULL"
            if numbers:
                values = f"site{site.number}_p{k}"
                out.append(f"static const double {values}[{len(numbers)}] = "
                           f"{{{', '.join(_double(v) for v in numbers)}}};")
            size = len(numbers) if numbers is not None else 1
            index = outputs.get(param.output, -1) if param.output else -1
            entries.append(f"{{{c_string(param.name)}, ORCCAD_GIVEN_{param.given.name}, {param.kind}, "
                           f"{size}, {values}, {c_string(param.text)}, {index}}}")
        params = "NULL"
        if entries:
            params = f"site{site.number}_params"
            out.append(f"static const orccad_site_param {params}[{len(entries)}] = {{\n    "
                       + ",\n    ".join(entries) + "\n};")
        rows.append(f"{{{c_string(site.task)}, {c_string(site.loc.file)}, {site.loc.line}, "
                    f"{site.loc.col}, {len(entries)}, {params}}}")
    body = ",\n    ".join(rows) or '{"", "", 0, 0, 0, NULL}'
    out.append(f"const orccad_site_info {prefix}_site_info[{max(1, len(sites))}] = {{\n"
               f"    {body}\n}};")
    return out


def site_comment(prefix: str, sites: tuple[SiteInfo, ...]) -> list[str]:
    """The header's comment lines: per site, what it starts and how it gives each
    parameter."""
    if not sites:
        return ["/* The mission has no run site. */"]
    lines = [f"/* What each run site starts ({prefix}_site_info[site]): its Robot-Task and every",
             "   parameter as the site gives it (= a constant written at the site, default:",
             "   the task's default, at start: computed when the task starts, carried by the",
             "   argument output named; its value here is the nominal default)."]
    for site in sites:
        lines.append(f"   site {site.number}: {c_comment(site.call_text())} at "
                     f"{c_comment(str(site.loc))}")
        for param in site.params:
            how = {Given.CONSTANT: "=", Given.DEFAULT: "default"}.get(param.given)
            if how is None:
                how = f"at start (output {param.output}), nominal"
            lines.append(f"       {c_comment(param.name)}: {how} {c_comment(param.text)}")
    lines[-1] += " */"
    return lines


def phase_columns(sites: tuple[SiteInfo, ...]) -> str:
    """The phase table's legend: one column per site, the site and what it starts."""
    columns = "; ".join(f"{s.number}: {s.call_text()}" for s in sites)
    return f"/* phase_table[state][site], 0 not running, 1-3 the phase; sites: " \
           f"{c_comment(columns)} */"
