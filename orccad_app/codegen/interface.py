"""The C interface of a generated automaton: field names, roles and the documented header.

Every input of the automaton is a ``bool`` presence field of ``PREFIX_in`` (and, when valued,
a ``_value`` field of its static type); every output likewise in ``PREFIX_out``. Names are the
signal names made C identifiers (``TrackPID.Saturated`` → ``TrackPID_Saturated``; ``s_``
before a name a header or the compiler owns, ``NAN`` → ``s_NAN``, :mod:`.names`; a suffix
added on a clash); the header says which signal each field is, its type and its role for a
runtime (start a Robot-Task, apply a type-1 update, an observer event to set…).
"""

from __future__ import annotations

from dataclasses import dataclass

from orccad_app.codegen.cexpr import c_comment, c_type
from orccad_app.codegen.names import c_identifier
from orccad_app.codegen.static_types import CType, Kind
from orccad_app.reactive import ir
from orccad_app.robottask.signals import RoleKind, SignalRoles

__all__ = ["CSignal", "Interface", "ROLE_CODES", "role_text"]

#: the role numbers of ``enum orccad_role`` in the header
ROLE_CODES: dict[RoleKind | None, int] = {
    None: 0, RoleKind.START: 1, RoleKind.MEASURE: 2, RoleKind.ACTIVATE: 3,
    RoleKind.GOOD_END: 4, RoleKind.EVENT: 5, RoleKind.ADJUST: 6, RoleKind.RAISED: 7,
    RoleKind.ARGUMENT: 8,
}


@dataclass(frozen=True)
class CSignal:
    """One interface signal: its C field (``field``, and ``field_value`` when valued)."""

    decl: ir.SignalDecl
    field: str
    ctype: CType | None  # None: pure
    role: RoleKind | None
    task: str | None
    detail: str | None

    @property
    def value_field(self) -> str:
        return f"{self.field}_value"

    def declaration(self) -> list[str]:
        """The struct member(s), each with its comment."""
        lines = [f"    bool {self.field}; /* {_comment(self)} */"]
        if self.ctype is not None:
            size = f"[{self.ctype.size}]" if self.ctype.kind is Kind.VECTOR else ""
            lines.append(f"    {c_type(self.ctype)} {self.value_field}{size}; "
                         f"/* its value: {_type_text(self.ctype)} */")
        return lines


def _type_text(ctype: CType) -> str:
    if ctype.kind is Kind.STRING:
        return "a string, as its index in PREFIX_string_names"
    return str(ctype)


def role_text(signal: CSignal) -> str:
    """What a runtime does with the signal."""
    task, detail = signal.task, signal.detail
    return {
        None: "",
        RoleKind.START: f"start Robot-Task {task} (all its phases begin: synchronizing)",
        RoleKind.MEASURE: f"Robot-Task {task} enters phase 2: start its measuring modules",
        RoleKind.ACTIVATE: f"Robot-Task {task} enters phase 3: start every module",
        RoleKind.GOOD_END: f"Robot-Task {task} ended normally",
        RoleKind.EVENT: f"set when the observer of {task}'s '{detail}' fires",
        RoleKind.ADJUST: f"apply the parameter update of {task}'s type-1 exception {detail}",
        RoleKind.RAISED: f"exception {detail} is raised (type 2 or 3)",
        RoleKind.ARGUMENT: f"the value of {task}'s parameter {detail} at its start",
    }[signal.role]


def _comment(signal: CSignal) -> str:
    text = signal.decl.name
    role = role_text(signal)
    if role:
        text += f": {role}"
    return c_comment(text)


@dataclass(frozen=True)
class Interface:
    """The inputs and outputs of the generated automaton, in declaration order."""

    inputs: tuple[CSignal, ...]
    outputs: tuple[CSignal, ...]

    @classmethod
    def make(cls, inputs: tuple[ir.SignalDecl, ...], outputs: tuple[ir.SignalDecl, ...],
             types: dict, roles: SignalRoles | None,
             macros: frozenset[str] = frozenset()) -> "Interface":
        """The fields of ``inputs`` and ``outputs``; ``macros``: the header's own, which no
        field may be."""
        def side(decls: tuple[ir.SignalDecl, ...]) -> tuple[CSignal, ...]:
            taken: set[str] = set()
            found = []
            for decl in decls:
                role = roles.get(decl.name) if roles is not None else None
                ctype = types.get(decl) if decl.valued else None
                if decl.valued and ctype is None:
                    ctype = None  # a valued output never given a value: presence only
                found.append(CSignal(decl, c_identifier(decl.name, taken, macros), ctype,
                                     role.kind if role else None,
                                     role.task if role else None,
                                     role.name if role else None))
            return tuple(found)
        return cls(side(inputs), side(outputs))
