"""A Module-Task kind's C, provided by its plugin: :class:`CImplementation`.

``orccad sil`` and ``orccad codegen --module-tasks`` run every Module-Task in C. A plugin's kind
runs there when the kind says where its C is (:attr:`ModuleKind.c_implementation
<orccad_app.control.module.ModuleKind.c_implementation>`), and is refused with its name and
the reason otherwise. The contract (docs/deploy.md, "A plugin kind's C"): one C99 file that
includes ``orccad_mt.h`` and defines

.. code-block:: c

    void PREFIX_init(orc_mt *m);                 /* at each activation, state already zeroed */
    void PREFIX_compute(orc_mt *m, double t_s);  /* one job: m->in[] -> m->out[] */

reading its inputs from ``m->in[]`` (in the kind's input port order; ``present`` 0: none
yet) and setting ``m->out[k].present`` and ``m->out[k].v`` for what it writes; no allocation,
no recursion, ``-std=c99 -Wall -Wextra -Werror -pedantic`` clean.

**Parameters and state, declared once.** A kind declares its parameters and its state as
typed fields (:class:`CField`: a name, ``double`` or ``int64``, a size); ``params`` then maps
each parameter field's name to its value for an instance. From that one declaration come the
parameter words the controller is sent (in declaration order, sizes checked: no offset is
written by hand) and the header ``PREFIX_kind.h`` generated beside the table
(:func:`kind_header`): one typed struct for the parameters and one for the state, and the
functions that read them from ``m`` and write the state back, which the kind's C includes::

    #include "low_pass_kind.h"
    void low_pass_compute(orc_mt *m, double t_s)
    {
        low_pass_params p = low_pass_params_of(m);   /* p.cutoff_hz */
        low_pass_state s = low_pass_state_of(m);     /* s.primed, s.y[...] */
        ...
        low_pass_save_state(m, &s);
    }

A kind without declared fields gives ``params`` as the parameter vector ``m->p`` itself (at
most 192 numbers) and keeps its state in ``m->s[]`` (160 doubles).
"""

from __future__ import annotations

import enum
import math
import re
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from orccad_app.control.errors import ControlError

__all__ = ["CField", "CFieldType", "CImplementation", "MAX_PARAM_WORDS", "MAX_STATE_WORDS",
           "kind_header"]

_IDENTIFIER = re.compile(r"[A-Za-z_][A-Za-z0-9_]{0,30}")
MAX_PARAM_WORDS = 192
"""Parameter words of a Module-Task in the C runtime (``ORC_MAX_PARAMS``)."""
MAX_STATE_WORDS = 160
"""State words of a Module-Task in the C runtime (``ORC_MAX_STATE``)."""
_EXACT_INT = 2 ** 53
"""The largest integer a parameter word (a double) holds exactly."""


class CFieldType(enum.Enum):
    """The C type of a declared field (every one an 8-byte word)."""

    DOUBLE = "double"
    """A real number: ``double``."""
    INT64 = "int64_t"
    """An integer (a count, a mode, a flag): ``int64_t``; as a parameter, within ±2⁵³."""


@dataclass(frozen=True)
class CField:
    """One declared parameter or state field of a kind's C.

    :param name: the field's C name (an identifier).
    :param type: its C type.
    :param size: 1 for a scalar, else the length of an array (``double y[16]``).
    :param doc: what it is, with its unit (a comment in the generated header).
    """

    name: str
    type: CFieldType = CFieldType.DOUBLE
    size: int = 1
    doc: str = ""

    def __post_init__(self) -> None:
        if not _IDENTIFIER.fullmatch(self.name):
            raise ControlError(f"C field {self.name!r}: not a C identifier of at most 31 "
                               f"characters")
        if not isinstance(self.size, int) or self.size < 1:
            raise ControlError(f"C field {self.name!r}: size {self.size!r} must be a positive "
                               f"integer")

    def declaration(self) -> str:
        """The field as a struct member."""
        array = f"[{self.size}]" if self.size > 1 else ""
        comment = f" /* {self.doc} */" if self.doc else ""
        return f"    {self.type.value} {self.name}{array};{comment}"


def _words(fields: tuple[CField, ...]) -> int:
    return sum(field.size for field in fields)


@dataclass(frozen=True)
class CImplementation:
    """Where a plugin kind's C is, what it declares and how an instance's parameters reach it
    (see the module docstring).

    :param source: the C99 file.
    :param prefix: the C identifier before ``_init`` and ``_compute`` (at most 31 characters),
        unique among the kinds of a mission.
    :param params: from the :class:`~orccad_app.control.module.ModuleInstance`, called at every
        start and type-1 update: with declared ``param_fields``, a mapping of each field's
        name to its value (a number, or a sequence of ``size`` numbers); without, the
        parameter vector ``m->p`` itself (at most 192 numbers).
    :param param_fields: the parameters, declared once (the words and the C struct follow).
    :param state_fields: the state, declared once (a C struct kept in ``m->s``).
    """

    source: Path
    prefix: str
    params: Callable[[Any], Sequence[float] | Mapping[str, Any]]
    param_fields: tuple[CField, ...] = ()
    state_fields: tuple[CField, ...] = ()

    def __post_init__(self) -> None:
        if not _IDENTIFIER.fullmatch(self.prefix):
            raise ControlError(f"C implementation: prefix {self.prefix!r} is not a C "
                               f"identifier of at most 31 characters")
        object.__setattr__(self, "source", Path(self.source))
        object.__setattr__(self, "param_fields", tuple(self.param_fields))
        object.__setattr__(self, "state_fields", tuple(self.state_fields))
        for what, fields, limit in (("parameter", self.param_fields, MAX_PARAM_WORDS),
                                    ("state", self.state_fields, MAX_STATE_WORDS)):
            names = [field.name for field in fields]
            twice = sorted({name for name in names if names.count(name) > 1})
            if twice:
                raise ControlError(f"C implementation {self.prefix}: {what} field(s) "
                                   f"{', '.join(twice)} declared twice")
            if _words(fields) > limit:
                raise ControlError(f"C implementation {self.prefix}: {_words(fields)} {what} "
                                   f"words declared, the C runtime holds {limit}")

    @property
    def declared(self) -> bool:
        """The kind declares its parameters and state (a generated header)."""
        return bool(self.param_fields or self.state_fields)

    @property
    def header_name(self) -> str:
        """The generated header's file name (``PREFIX_kind.h``)."""
        return f"{self.prefix}_kind.h"

    def words(self, instance: Any) -> tuple[float, ...]:
        """The parameter words of ``instance`` sent to the controller: the declared fields'
        values in declaration order (each checked against its type and size), or the
        undeclared vector as given. Raises :class:`ControlError` naming the field."""
        given = self.params(instance)
        if not self.param_fields:
            if isinstance(given, Mapping):
                raise ControlError(f"C implementation {self.prefix}: params gives a mapping "
                                   f"but the kind declares no parameter fields")
            return tuple(float(value) for value in given)
        if not isinstance(given, Mapping):
            raise ControlError(f"C implementation {self.prefix}: params must give a mapping "
                               f"of the declared fields' names to their values")
        unknown = sorted(set(given) - {field.name for field in self.param_fields})
        if unknown:
            raise ControlError(f"C implementation {self.prefix}: params gives undeclared "
                               f"field(s) {', '.join(map(str, unknown))}")
        words: list[float] = []
        for field in self.param_fields:
            if field.name not in given:
                raise ControlError(f"C implementation {self.prefix}: params gives no value "
                                   f"for field {field.name!r}")
            words += _field_words(self.prefix, field, given[field.name])
        return tuple(words)


def _field_words(prefix: str, field: CField, value: Any) -> list[float]:
    """The words of ``value`` for ``field``: ``size`` numbers, integers exact."""
    items = list(value) if field.size > 1 else [value]
    if field.size > 1 and len(items) != field.size:
        raise ControlError(f"C implementation {prefix}: field {field.name!r} takes "
                           f"{field.size} numbers, got {len(items)}")
    words = []
    for item in items:
        try:
            number = float(item)
        except (TypeError, ValueError):
            raise ControlError(f"C implementation {prefix}: field {field.name!r}: {item!r} is "
                               f"not a number") from None
        if field.type is CFieldType.INT64 and not (
                math.isfinite(number) and number == int(number) and abs(number) <= _EXACT_INT):
            raise ControlError(f"C implementation {prefix}: field {field.name!r} is an "
                               f"int64: {item!r} is not an integer within ±2^53")
        words.append(number)
    return words


def _reads(fields: tuple[CField, ...], source: str) -> list[str]:
    """Statements filling struct ``v`` from the words ``source[...]``."""
    lines, at = [], 0
    for field in fields:
        cast = "(int64_t)" if field.type is CFieldType.INT64 else ""
        if field.size == 1:
            lines.append(f"    v.{field.name} = {cast}{source}[{at}];")
        else:
            lines.append(f"    for (i = 0; i < {field.size}; i++) {{ v.{field.name}[i] = "
                         f"{cast}{source}[{at} + i]; }}")
        at += field.size
    return lines


def kind_header(c: CImplementation) -> str:
    """``PREFIX_kind.h``: the kind's parameters and state as typed structs, from their one
    declaration (:class:`CField`), and the functions that read them from a Module-Task and
    write its state back (the parameters are read from their words, the state is kept in
    ``m->s`` as its bytes)."""
    p, guard = c.prefix, f"ORCCAD_KIND_{c.prefix.upper()}_H"
    params = [field.declaration() for field in c.param_fields] or ["    char unused;"]
    state = [field.declaration() for field in c.state_fields] or ["    char unused;"]
    any_array = any(field.size > 1 for field in c.param_fields)
    lines = [
        f"/* GENERATED by orccad from the declaration of kind prefix {p} "
        f"(CImplementation.param_fields, state_fields): do not edit. */",
        f"#ifndef {guard}", f"#define {guard}", "", "#include <stdint.h>", "#include <string.h>",
        "", '#include "orccad_mt.h"', "",
        "typedef struct {", *params, f"}} {p}_params;", "",
        "typedef struct {", *state, f"}} {p}_state;", "",
        f"/* the state fits ORC_MAX_STATE words ({_words(c.state_fields)} declared) */",
        f"typedef char {p}_state_fits[sizeof({p}_state) <= sizeof(((orc_mt *)0)->s) ? 1 : -1];",
        "",
        f"static inline {p}_params {p}_params_of(const orc_mt *m)",
        "{",
        f"    {p}_params v;",
        *(["    int i;"] if any_array else []),
        "    memset(&v, 0, sizeof v);",
        *_reads(c.param_fields, "m->p"),
        "    return v;",
        "}", "",
        f"static inline {p}_state {p}_state_of(const orc_mt *m)",
        "{",
        f"    {p}_state v;",
        "    memcpy(&v, m->s, sizeof v);",
        "    return v;",
        "}", "",
        f"static inline void {p}_save_state(orc_mt *m, const {p}_state *v)",
        "{",
        "    memcpy(m->s, v, sizeof *v);",
        "}", "",
        "#endif", ""]
    return "\n".join(lines)
